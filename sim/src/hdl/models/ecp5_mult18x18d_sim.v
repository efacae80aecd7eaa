// Behavioural model of the Lattice ECP5 `MULT18X18D` multiplier, for
// simulation and lint of the Verilog that `rtl::dsp_multiplier` generates
// (co-simulation under Icarus and Verilator, Verilator lint, Yosys latch
// check). Synthesis for the ECP5 never reads it: Yosys's `synth_ecp5` and
// nextpnr take the primitive itself. The `generic` target puts it, renamed
// `top$NAME`, inside the block as behavioural Verilog for any synthesis
// tool (`sim::hdl::primitives::to_generic`).
//
// It models what `DspMultiplier` uses: unsigned operands (`SIGNEDA`,
// `SIGNEDB` low), A and B from the ports (`SOURCEA`, `SOURCEB` low), the
// input registers on `CLK0` (`REG_INPUTA_CLK`, `REG_INPUTB_CLK` = "CLK0",
// enable `CE0`), no pipeline or output register: `P` is the product of the
// two input registers. The C port, the other clocks, enables and resets
// are tied off. Anything else stops the simulation with an error. The
// registers start at zero, as the rust-hdl model's do.
/* verilator lint_off UNUSEDSIGNAL */
/* verilator lint_off UNUSEDPARAM */
module MULT18X18D(
  input A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0,
  input B17, B16, B15, B14, B13, B12, B11, B10, B9, B8, B7, B6, B5, B4, B3, B2, B1, B0,
  input C17, C16, C15, C14, C13, C12, C11, C10, C9, C8, C7, C6, C5, C4, C3, C2, C1, C0,
  input SIGNEDA, SIGNEDB, SOURCEA, SOURCEB,
  input CLK0, CLK1, CLK2, CLK3,
  input CE0, CE1, CE2, CE3,
  input RST0, RST1, RST2, RST3,
  output P35, P34, P33, P32, P31, P30, P29, P28, P27, P26, P25, P24, P23, P22, P21, P20, P19, P18, P17, P16, P15, P14, P13, P12, P11, P10, P9, P8, P7, P6, P5, P4, P3, P2, P1, P0
);
  // Defaults: the modelled use (Yosys elaborates the model once with them).
  parameter REG_INPUTA_CLK = "CLK0";
  parameter REG_INPUTA_CE = "CE0";
  parameter REG_INPUTA_RST = "RST0";
  parameter REG_INPUTB_CLK = "CLK0";
  parameter REG_INPUTB_CE = "CE0";
  parameter REG_INPUTB_RST = "RST0";
  parameter REG_INPUTC_CLK = "NONE";
  parameter REG_PIPELINE_CLK = "NONE";
  parameter REG_OUTPUT_CLK = "NONE";
  parameter CLK0_DIV = "ENABLED";
  parameter CLK1_DIV = "ENABLED";
  parameter CLK2_DIV = "ENABLED";
  parameter CLK3_DIV = "ENABLED";
  parameter HIGHSPEED_CLK = "NONE";
  parameter GSR = "ENABLED";
  parameter CAS_MATCH_REG = "FALSE";
  parameter MULT_BYPASS = "DISABLED";
  parameter RESETMODE = "SYNC";
  parameter SOURCEB_MODE = "B_SHIFT";

  wire [17:0] a = {A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0};
  wire [17:0] b = {B17, B16, B15, B14, B13, B12, B11, B10, B9, B8, B7, B6, B5, B4, B3, B2, B1, B0};
  reg [17:0] a_q;
  reg [17:0] b_q;
  assign {P35, P34, P33, P32, P31, P30, P29, P28, P27, P26, P25, P24, P23, P22, P21, P20, P19, P18, P17, P16, P15, P14, P13, P12, P11, P10, P9, P8, P7, P6, P5, P4, P3, P2, P1, P0} = a_q * b_q;
  initial begin
    if (REG_INPUTA_CLK != "CLK0" || REG_INPUTB_CLK != "CLK0" || REG_PIPELINE_CLK != "NONE" || REG_OUTPUT_CLK != "NONE") begin
      $display("MULT18X18D model: only the input-registered use of rtl::dsp_multiplier is modelled");
      $finish;
    end
    a_q = 18'b0;
    b_q = 18'b0;
  end
  always @(posedge CLK0) begin
    if (CE0 && !SIGNEDA && !SOURCEA) a_q <= a;
    if (CE0 && !SIGNEDB && !SOURCEB) b_q <= b;
  end
endmodule
/* verilator lint_on UNUSEDPARAM */
/* verilator lint_on UNUSEDSIGNAL */
