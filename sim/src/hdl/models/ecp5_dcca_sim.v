// Behavioural model of the Lattice ECP5 `DCCA` clock buffer, for
// simulation and lint of the Verilog that `rtl::primitives::reset_buffer`
// generates (co-simulation under Icarus and Verilator, Verilator lint,
// Yosys latch check). Synthesis for the ECP5 never reads it: Yosys's
// `synth_ecp5` and nextpnr take the primitive itself. The `generic` target
// puts it, renamed `top$NAME`, inside the block (a wire for any synthesis
// tool; `sim::hdl::primitives::to_generic`).
//
// `CLKO` is `CLKI` while `CE` is high, as `ResetBuffer` uses it (`CE` tied
// high); the real buffer's glitch-free gating of `CE` is not modelled.
module DCCA(
  input CLKI,
  input CE,
  output CLKO
);
  assign CLKO = CLKI & CE;
endmodule
