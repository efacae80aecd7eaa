//! # primitives — simulation models of the vendor primitives in generated Verilog
//!
//! Some blocks instantiate an ECP5 primitive by name (`rtl::primitives::block_ram`: the
//! `DP16KD` block RAM with its output register, which Yosys never infers;
//! `rtl::primitives::dsp_multiplier`: the `MULT18X18D` with its input registers;
//! `rtl::primitives::lut_ram`: the `TRELLIS_DPR16X4` LUT RAM of the gain cells' rows;
//! `rtl::primitives::reset_buffer`: the `DCCA` that puts the line processor's reset on a
//! global net).
//! Yosys's `synth_ecp5` maps them itself; the co-simulation (Icarus,
//! Verilator), the lint and the latch check read the behavioural models here
//! beside the design, as `models.v`.

/// Behavioural model of `DP16KD` as `rtl::primitives::block_ram::BlockRam` uses it.
const DP16KD_MODEL: &str = include_str!("models/ecp5_dp16kd_sim.v");

/// Behavioural model of `MULT18X18D` as `rtl::primitives::dsp_multiplier::DspMultiplier` uses it.
const MULT18X18D_MODEL: &str = include_str!("models/ecp5_mult18x18d_sim.v");

/// Behavioural model of `TRELLIS_DPR16X4` as `rtl::primitives::lut_ram::LutRam` uses it.
const DPR16X4_MODEL: &str = include_str!("models/ecp5_dpr16x4_sim.v");

/// Behavioural model of `DCCA` as `rtl::primitives::reset_buffer::ResetBuffer` uses it.
const DCCA_MODEL: &str = include_str!("models/ecp5_dcca_sim.v");

/// The file the models are written to beside `top.v`.
pub(crate) const MODELS_FILE: &str = "models.v";

/// The primitives with a model: the module name, the model's text.
const MODELS: [(&str, &str); 4] =
    [("DP16KD", DP16KD_MODEL), ("MULT18X18D", MULT18X18D_MODEL), ("TRELLIS_DPR16X4", DPR16X4_MODEL), ("DCCA", DCCA_MODEL)];

/// Whether `line` of rust-hdl's Verilog starts an instance of primitive
/// `name` (`    NAME #(` or `    NAME inst (`; not the generic target's
/// `top$NAME`, not a comment or a module header).
fn starts_instance(line: &str, name: &str) -> bool {
    line.trim_start().strip_prefix(name).is_some_and(|rest| rest.starts_with(' '))
}

/// Whether `design` instantiates primitive `name` (its Verilog holds a
/// line `    NAME #(` or `    NAME inst (`).
pub fn instantiates(design: &str, name: &str) -> bool {
    design.lines().any(|line| starts_instance(line, name))
}

/// The simulation model of primitive `name`, if it has one.
pub(crate) fn model(name: &str) -> Option<&'static str> {
    MODELS.into_iter().find(|(n, _)| *n == name).map(|(_, text)| text)
}

/// The primitives `design` instantiates, each with its model's text (one
/// module a model, named as the primitive).
pub(crate) fn models_used(design: &str) -> Vec<(&'static str, &'static str)> {
    MODELS.into_iter().filter(|(name, _)| instantiates(design, name)).collect()
}

/// `design` (rust-hdl's Verilog, top module `top`) for the `generic`
/// target: each primitive it instantiates becomes its model, renamed
/// `top$NAME` and appended to the design, so that the design is one
/// self-contained file of behavioural Verilog (memories with registered
/// reads, `*`) which Yosys, Vivado and Quartus infer, and which no other
/// block's file collides with once the block is renamed. The logic is the
/// models', which the co-simulation checks against the rust-hdl model.
pub(crate) fn to_generic(design: &str) -> String {
    let used = models_used(design);
    let stand_in = |name: &str| format!("{}${name}", super::cosim::TOP_MODULE);
    let mut text: String = design
        .split_inclusive('\n')
        .map(|line| match used.iter().find(|(name, _)| starts_instance(line, name)) {
            Some((name, _)) => line.replacen(name, &stand_in(name), 1),
            None => line.to_string(),
        })
        .collect();
    for (name, model) in used {
        text.push('\n');
        text.push_str(&model.replacen(&format!("module {name}("), &format!("module {}(", stand_in(name)), 1));
    }
    text
}

/// The models of the primitives `design` instantiates, as one Verilog text
/// (empty when it instantiates none).
pub(crate) fn models_for(design: &str) -> String {
    models_used(design).into_iter().map(|(_, text)| text).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_design_gets_the_model_of_the_primitive_it_instantiates_and_no_other() {
        assert!(models_for("    DP16KD #(\n.DATA_WIDTH_A(18)) ram_0 ();").contains("module DP16KD("));
        assert!(!models_for("    DP16KD #(\n.DATA_WIDTH_A(18)) ram_0 ();").contains("module MULT18X18D("));
        assert!(models_for("    MULT18X18D #(\n.REG_INPUTA_CLK(\"CLK0\")) mult ();").contains("module MULT18X18D("));
        assert!(models_for("    TRELLIS_DPR16X4 #(\n.WCKMUX(\"WCK\")) ram_0 ();").contains("module TRELLIS_DPR16X4("));
        assert!(!models_for("    TRELLIS_DPR16X4 #(\n.WCKMUX(\"WCK\")) ram_0 ();").contains("module DP16KD("));
        assert_eq!(models_for("module top(clock); endmodule"), "");
        assert!(models_for("    DCCA reset_dcca (.CLKI(reset_in), .CE(1'b1), .CLKO(reset));").contains("module DCCA("));
        // A comment naming a primitive is no instance of it.
        assert_eq!(models_for("    // a DCCA puts the reset on a global net\n    /* DP16KD */"), "");
    }

    #[test]
    fn the_generic_target_instantiates_renamed_models_and_no_primitive() {
        let design = "module top(clock);\n    DP16KD #(\n.DATA_WIDTH_A(18)) ram_0 ();\n    DP16KD #(\n.DATA_WIDTH_A(9)) ram_1 ();\nendmodule // top\n";
        let g = to_generic(design);
        assert_eq!(g.matches(" top$DP16KD #(").count(), 2);
        assert_eq!(g.matches("module top$DP16KD(").count(), 1);
        assert!(!g.contains("module DP16KD(") && !g.contains("MULT18X18D"));
        // No primitive is left for the ECP5 models to stand in for.
        assert_eq!(models_for(&g), "");
        assert_eq!(to_generic("module top(clock); endmodule"), "module top(clock); endmodule");
        let g = to_generic("module top(reset_in, reset);\n    DCCA reset_dcca (.CLKI(reset_in), .CE(1'b1), .CLKO(reset));\nendmodule // top\n");
        assert!(g.contains("    top$DCCA reset_dcca (") && g.contains("module top$DCCA(") && !instantiates(&g, "DCCA"));
    }
}
