//! Tests of the co-simulation harness (`sim::hdl::cosim`) on a small block: an
//! 8-bit accumulator with enable, a registered comparator, a 64-bit
//! registered adder and a 16×8 block RAM (`rust_hdl::widgets` `RAM`).
//! Icarus Verilog and Verilator must reproduce the Rust simulation exactly.

use std::path::{Path, PathBuf};
use std::time::Instant;

use rust_hdl::prelude::*;
use sim::hdl::cosim::{self, CosimError, Options, Port, Simulator, Trace};

/// The test block. `rdata` is gated by `started` so that the RAM's
/// undefined output before the first clock edge (X in Icarus) is not seen.
#[derive(LogicBlock)]
struct Acc {
    pub clock: Signal<In, Clock>,
    pub enable: Signal<In, Bit>,
    pub data: Signal<In, Bits<8>>,
    pub threshold: Signal<In, Bits<8>>,
    pub we: Signal<In, Bit>,
    pub waddr: Signal<In, Bits<4>>,
    pub raddr: Signal<In, Bits<4>>,
    pub wide_in: Signal<In, Bits<64>>,
    pub sum: Signal<Out, Bits<8>>,
    pub above: Signal<Out, Bit>,
    pub rdata: Signal<Out, Bits<8>>,
    pub wide_out: Signal<Out, Bits<64>>,
    acc: DFF<Bits<8>>,
    gt: DFF<Bit>,
    wide: DFF<Bits<64>>,
    started: DFF<Bit>,
    ram: RAM<Bits<8>, 4>,
}

impl Logic for Acc {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, acc, gt, wide, started);
        self.ram.read_clock.next = self.clock.val();
        self.ram.write_clock.next = self.clock.val();
        if self.enable.val() {
            self.acc.d.next = self.acc.q.val() + self.data.val();
        }
        self.gt.d.next = self.acc.q.val() > self.threshold.val();
        self.wide.d.next = self.wide_in.val() + bit_cast::<64, 8>(self.acc.q.val());
        self.ram.write_enable.next = self.we.val();
        self.ram.write_address.next = self.waddr.val();
        self.ram.write_data.next = self.acc.q.val();
        self.ram.read_address.next = self.raddr.val();
        self.sum.next = self.acc.q.val();
        self.above.next = self.gt.q.val();
        self.started.d.next = true;
        if self.started.q.val() {
            self.rdata.next = self.ram.read_data.val();
        } else {
            self.rdata.next = 0.into();
        }
        self.wide_out.next = self.wide.q.val();
    }
}

impl Default for Acc {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            enable: Default::default(),
            data: Default::default(),
            threshold: Default::default(),
            we: Default::default(),
            waddr: Default::default(),
            raddr: Default::default(),
            wide_in: Default::default(),
            sum: Default::default(),
            above: Default::default(),
            rdata: Default::default(),
            wide_out: Default::default(),
            acc: Default::default(),
            gt: Default::default(),
            wide: Default::default(),
            started: Default::default(),
            ram: RAM::from((0..16u64).map(|i| Bits::<8>::from(i * 7 + 3))),
        }
    }
}

fn input_ports() -> Vec<Port> {
    cosim::ports(&[
        ("enable", 1),
        ("data", 8),
        ("threshold", 8),
        ("we", 1),
        ("waddr", 4),
        ("raddr", 4),
        ("wide_in", 64),
    ])
}

fn output_ports() -> Vec<Port> {
    cosim::ports(&[("sum", 8), ("above", 1), ("rdata", 8), ("wide_out", 64)])
}

/// xorshift64*: deterministic pseudo-random stimulus without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
}

/// `n` cycles of stimulus: random values, with an idle stretch (all inputs
/// constant, enable low) in the middle so that the run-length lines of the
/// vector format are exercised.
fn stimulus(n: usize, seed: u64) -> Vec<Vec<u64>> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|k| {
            if (n / 2..n / 2 + 20).contains(&k) {
                return vec![0, 0, 0x80, 0, 0, 0, 0];
            }
            let r = rng.next();
            let wide = rng.next();
            vec![
                (r & 3 != 0) as u64, // enable 3/4 of the time
                (r >> 8) & 0xff,     // data
                (r >> 16) & 0xff,    // threshold
                (r >> 24) & 1,       // we
                (r >> 28) & 0xf,     // waddr
                (r >> 32) & 0xf,     // raddr
                if k % 7 == 0 {
                    u64::MAX - (r >> 40)
                } else {
                    wide
                }, // wide_in, with carries near 2^64
            ]
        })
        .collect()
}

fn record_acc(stim: Vec<Vec<u64>>) -> (Acc, Trace) {
    let mut uut = Acc::default();
    let trace = cosim::record(
        &mut uut,
        &input_ports(),
        &output_ports(),
        |u: &mut Acc, level| u.clock.next = level.into(),
        |u: &mut Acc, v: &[u64]| {
            u.enable.next = v[0] != 0;
            u.data.next = v[1].into();
            u.threshold.next = v[2].into();
            u.we.next = v[3] != 0;
            u.waddr.next = v[4].into();
            u.raddr.next = v[5].into();
            u.wide_in.next = v[6].into();
        },
        |u: &Acc| {
            vec![
                u.sum.val().index() as u64,
                u.above.val() as u64,
                u.rdata.val().index() as u64,
                u.wide_out.val().to_u64(),
            ]
        },
        stim,
    )
    .expect("record");
    (uut, trace)
}

/// The block's Verilog, from a fresh block (see `cosim::verilog_of`).
fn verilog() -> String {
    cosim::verilog_of(Acc::default())
}

fn vectors_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../vectors/harness")
}

/// An independent model of the block, to check that `record` samples where
/// the documented cycle semantics says.
fn model(stim: &[Vec<u64>]) -> Vec<Vec<u64>> {
    let (mut acc, mut gt, mut wide, mut started, mut rd) = (0u64, 0u64, 0u64, false, 0u64);
    let mut mem: Vec<u64> = (0..16).map(|i| i * 7 + 3).collect();
    let mut out = Vec::new();
    for v in stim {
        out.push(vec![acc, gt, if started { rd } else { 0 }, wide]);
        let (en, data, th, we, wa, ra, wi) = (v[0], v[1], v[2], v[3], v[4], v[5], v[6]);
        let next_acc = if en != 0 { (acc + data) & 0xff } else { acc };
        gt = (acc > th) as u64;
        wide = wi.wrapping_add(acc);
        rd = mem[ra as usize];
        if we != 0 {
            mem[wa as usize] = acc;
        }
        started = true;
        acc = next_acc;
    }
    out
}

#[test]
fn cosim_record_follows_the_cycle_semantics() {
    let stim = stimulus(500, 0x1234_5678_9abc_def1);
    let (_, trace) = record_acc(stim.clone());
    assert_eq!(trace.len(), 500);
    let want = model(&stim);
    if let Err(m) = cosim::compare(&trace, &want) {
        panic!("record differs from the hand model: {m}");
    }
    // The trace is not trivial: every output changes.
    for j in 0..trace.outputs.len() {
        let distinct: std::collections::BTreeSet<u64> =
            trace.cycles.iter().map(|c| c.outputs[j]).collect();
        assert!(
            distinct.len() > 1,
            "output {} is constant",
            trace.outputs[j].name
        );
    }
}

#[test]
fn cosim_record_speed() {
    let n = 100_000;
    let stim = stimulus(n, 7);
    let t = Instant::now();
    let (_, trace) = record_acc(stim);
    let s = t.elapsed().as_secs_f64();
    eprintln!(
        "record: {n} cycles in {s:.3} s = {:.0} cycles/s",
        n as f64 / s
    );
    assert_eq!(trace.len(), n);
}

fn check_sim(sim: Simulator, design: &str, trace: &Trace) {
    match cosim::check(sim, design, trace, &Options::default()) {
        Ok(r) => eprintln!(
            "{}: {} cycles, compile {:.2} s, run {:.3} s",
            sim.name(),
            trace.len(),
            r.compile.as_secs_f64(),
            r.run.as_secs_f64()
        ),
        Err(e) => panic!("{e}"),
    }
}

#[test]
fn cosim_icarus_reproduces_the_rust_trace() {
    let (simulated, trace) = record_acc(stimulus(400, 0xfeed_beef));
    // The trap `verilog_of` avoids: the RAM of a simulated block writes its
    // current contents as the Verilog initial values.
    assert_ne!(
        generate_verilog(&simulated),
        verilog(),
        "the RAM was written"
    );
    check_sim(Simulator::Icarus, &verilog(), &trace);
}

#[test]
fn cosim_verilator_reproduces_the_rust_trace() {
    let (_, trace) = record_acc(stimulus(400, 0xfeed_beef));
    check_sim(Simulator::Verilator, &verilog(), &trace);
}

/// The intended flow for real blocks: committed vectors, replayed by the
/// Rust model and by both simulators. `COSIM_BLESS=1` rewrites the file.
#[test]
fn cosim_committed_vectors_replay_in_rust_icarus_and_verilator() {
    let (_, fresh) = record_acc(stimulus(300, 42));
    let path = vectors_dir().join("acc.trace");
    let committed = cosim::committed_trace(&path, &fresh).unwrap_or_else(|e| panic!("{e}"));
    let design = verilog();
    let opts = Options::default();
    cosim::check(Simulator::Icarus, &design, &committed, &opts).unwrap_or_else(|e| panic!("{e}"));
    cosim::check(Simulator::Verilator, &design, &committed, &opts)
        .unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn cosim_compare_catches_a_changed_value() {
    let (_, trace) = record_acc(stimulus(300, 99));
    let mut got = trace.expected();
    assert!(cosim::compare(&trace, &got).is_ok());
    got[123][2] ^= 0x10;
    got[200][0] ^= 1;
    let m = cosim::compare(&trace, &got).expect_err("a changed value must be caught");
    let d = m.first.clone().expect("a first difference");
    assert_eq!((d.cycle, d.port.as_str()), (123, "rdata"));
    assert_eq!(d.got, d.expected ^ 0x10);
    assert_eq!(m.differing_cycles, 2);
    let msg = m.to_string();
    assert!(
        msg.contains("cycle 123") && msg.contains("`rdata`") && msg.contains("2 of 300"),
        "{msg}"
    );
    // A missing cycle is caught too.
    let short = &trace.expected()[..299];
    let m = cosim::compare(&trace, short).expect_err("a missing cycle must be caught");
    assert!(
        m.first.is_none() && m.to_string().contains("300 cycles expected, 299 obtained"),
        "{m}"
    );
}

/// A design changed after recording (sum off by one from cycle 0) is caught
/// by the simulator run, not only by `compare` on hand-edited values.
#[test]
fn cosim_icarus_catches_a_changed_design() {
    let (_, trace) = record_acc(stimulus(100, 5));
    let design = verilog().replace("sum = acc$q;", "sum = acc$q + 8'h1;");
    assert!(
        design.contains("acc$q + 8'h1"),
        "the design text changed shape"
    );
    match cosim::check(Simulator::Icarus, &design, &trace, &Options::default()) {
        Err(CosimError::Mismatch { mismatch, dir, .. }) => {
            let _ = std::fs::remove_dir_all(dir);
            let d = mismatch.first.expect("a first difference");
            assert_eq!(
                (d.cycle, d.port.as_str(), d.expected, d.got),
                (0, "sum", 0, 1)
            );
            assert_eq!(mismatch.differing_cycles, 100);
        }
        other => panic!("expected a mismatch, got {other:?}"),
    }
}

/// X on an output (an uninitialised register in hand-written Verilog) is an
/// error that names the cycle and port, in Icarus (4-state).
#[test]
fn cosim_icarus_reports_unknown_outputs() {
    let design = "module top(clock, a, y);\n  input wire clock;\n  input wire [7:0] a;\n  output reg [7:0] y;\n  always @(posedge clock) y <= a;\nendmodule\n";
    let mut trace = Trace::new(cosim::ports(&[("a", 8)]), cosim::ports(&[("y", 8)])).unwrap();
    trace.push(vec![5], vec![0]).unwrap();
    trace.push(vec![6], vec![5]).unwrap();
    match cosim::run(Simulator::Icarus, design, &trace, &Options::default()) {
        Err(e @ CosimError::Unknown { .. }) => {
            let msg = e.to_string();
            assert!(
                msg.contains("`y`") && msg.contains("cycle 0") && msg.contains("1 of 2"),
                "{msg}"
            );
            if let CosimError::Unknown { dir, .. } = e {
                let _ = std::fs::remove_dir_all(dir);
            }
        }
        other => panic!("expected CosimError::Unknown, got {other:?}"),
    }
}

#[test]
fn cosim_ports_of_the_design_are_checked() {
    let (_, trace) = record_acc(stimulus(10, 1));
    let design = verilog();
    let (ins, outs) = cosim::top_ports(&design).unwrap();
    assert_eq!(
        ins[0],
        Port {
            name: "clock".into(),
            width: 1
        }
    );
    assert_eq!(&ins[1..], &input_ports()[..]);
    assert_eq!(outs, output_ports());
    let mut wrong = trace.clone();
    wrong.outputs[3].width = 63;
    for c in &mut wrong.cycles {
        c.outputs[3] &= (1 << 63) - 1;
    }
    let e = cosim::run(Simulator::Icarus, &design, &wrong, &Options::default()).unwrap_err();
    assert!(
        matches!(e, CosimError::PortsDiffer(_))
            && e.to_string()
                .contains("`wide_out` is 64 bits in the design, 63 in the trace"),
        "{e}"
    );
}

#[test]
fn cosim_vector_file_round_trip() {
    let (_, trace) = record_acc(stimulus(300, 3));
    let text = trace.to_text();
    assert!(
        text.contains("\n*18\n"),
        "the idle stretch is run-length coded:\n{text}"
    );
    assert_eq!(Trace::from_text(&text, "text").unwrap(), trace);

    let dir = tempfile::tempdir().unwrap();
    let one = dir.path().join("sub/acc.trace");
    trace.write(&one).unwrap();
    assert_eq!(Trace::read(&one).unwrap(), trace);
    let (ins, outs) = (dir.path().join("acc.in"), dir.path().join("acc.out"));
    trace.write_inputs(&ins).unwrap();
    trace.write_expected(&outs).unwrap();
    assert!(!std::fs::read_to_string(&ins).unwrap().contains('|'));
    assert_eq!(Trace::read_split(&ins, &outs).unwrap(), trace);

    // Hand-written text: comments, repeat lines, 64-bit values.
    let hand = "# comment\ninputs a:1 b:64\noutputs y:4\ncycles 4\n1 ffffffffffffffff | f\n# inside\n*2\n0 0 | 0\n";
    let t = Trace::from_text(hand, "hand").unwrap();
    assert_eq!(t.len(), 4);
    assert_eq!(t.cycles[2].inputs, vec![1, u64::MAX]);
    assert_eq!(t.cycles[3].outputs, vec![0]);

    // Malformed files are errors with a line number.
    for (bad, what) in [
        (hand.replace("cycles 4", "cycles 5"), "the header says 5"),
        (hand.replace("| f", "| 1f"), "does not fit port `y`"),
        (hand.replace("| f", "f"), "no `|`"),
        (hand.replace("b:64", "b:65"), "not in 1..=64"),
        (hand.replace("1 ffff", "1 fg ffff"), "not a hex value"),
        (hand.replace("0 0 | 0", "0 | 0"), "1 values for 2 ports"),
    ] {
        let e = Trace::from_text(&bad, "bad").expect_err(what).to_string();
        assert!(e.contains(what) && e.contains("line"), "{what}: {e}");
    }
}

/// Verilator's -Wall lint of the block's Verilog: only accepted codes.
/// rust-hdl writes `bit_cast` as a 64-bit mask, which Verilator calls WIDTH.
#[test]
fn cosim_lint_with_an_accepted_list() {
    let (_, _) = record_acc(stimulus(1, 1));
    let warnings = cosim::lint_verilator(&verilog()).unwrap_or_else(|e| panic!("{e}"));
    for w in &warnings {
        eprintln!("{w}");
    }
    assert!(
        warnings
            .iter()
            .any(|w| w.code == "WIDTH" && w.file == "top.v" && w.line > 0),
        "the bit_cast WIDTH warning is found and parsed: {warnings:?}"
    );
    let accepted = [("WIDTH", "rust-hdl's bit_cast masks with a 64-bit literal")];
    let counts = cosim::check_accepted(&warnings, &accepted).unwrap_or_else(|e| panic!("{e}"));
    assert!(counts["WIDTH"] >= 1);
    // Nothing accepted: the same warnings fail, and the message names them.
    let e = cosim::check_accepted(&warnings, &[])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("WIDTH") && e.contains("not in the accepted list"),
        "{e}"
    );
    // An undeclared identifier is a lint error, not a warning.
    let bad = "module top(clock, y);\n  input wire clock;\n  output reg y;\n  always @(*) y = nowhere;\nendmodule\n";
    match cosim::lint_verilator(bad) {
        Err(CosimError::LintErrors { log, dir }) => {
            let _ = std::fs::remove_dir_all(dir);
            assert!(log.contains("nowhere"), "{log}");
        }
        other => panic!("expected a lint error, got {other:?}"),
    }
}

/// A missing tool is an error whose message gives the install command (the
/// commands are pointed at names that do not exist).
#[test]
fn cosim_missing_tool_names_the_install_command() {
    let (_, trace) = record_acc(stimulus(10, 1));
    let design = verilog();
    let missing = "cosim-no-such-simulator";
    let opts = Options {
        iverilog: missing.into(),
        vvp: missing.into(),
        verilator: missing.into(),
        ..Options::default()
    };
    for sim in [Simulator::Icarus, Simulator::Verilator] {
        match cosim::run(sim, &design, &trace, &opts) {
            Err(e @ CosimError::ToolMissing { .. }) => {
                let msg = e.to_string();
                assert!(
                    msg.contains(missing) && msg.contains("apt-get install -y iverilog verilator"),
                    "{msg}"
                );
            }
            other => panic!("{}: expected ToolMissing, got {other:?}", sim.name()),
        }
    }
    let e = cosim::lint_verilator_with(&design, &opts).unwrap_err();
    assert!(matches!(e, CosimError::ToolMissing { .. }), "{e}");
}
