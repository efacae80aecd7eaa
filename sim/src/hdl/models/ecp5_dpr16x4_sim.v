// Behavioural model of the Lattice ECP5 `TRELLIS_DPR16X4` LUT RAM, for
// simulation and lint of the Verilog that `rtl::lut_ram` generates
// (co-simulation under Icarus and Verilator, Verilator lint, Yosys latch
// check). Synthesis for the ECP5 never reads it: Yosys's `synth_ecp5` and
// nextpnr take the primitive itself. The `generic` target puts it, renamed
// `top$NAME`, inside the block as behavioural Verilog for any synthesis
// tool (`sim::hdl::primitives::to_generic`).
//
// 16 words of 4 bits: a write of `DI` at `WAD` on the rising edge of `WCK`
// while `WRE` is high (`WCKMUX` = "WCK", `WREMUX` = "WRE", the only use
// modelled), an asynchronous read of the word at `RAD` on `DO`. The words
// start at `INITVAL` (word k in bits 4k+3..4k), zero as `LutRam` uses it.
/* verilator lint_off UNUSEDPARAM */
module TRELLIS_DPR16X4(
  input [3:0] DI,
  input [3:0] WAD,
  input WRE,
  input WCK,
  input [3:0] RAD,
  output [3:0] DO
);
  parameter WCKMUX = "WCK";
  parameter WREMUX = "WRE";
  parameter [63:0] INITVAL = 64'h0000000000000000;
  reg [3:0] mem [0:15];
  integer k;
  initial begin
    if (WCKMUX != "WCK" || WREMUX != "WRE") begin
      $display("TRELLIS_DPR16X4 model: only WCKMUX = \"WCK\", WREMUX = \"WRE\" are modelled");
      $finish;
    end
    for (k = 0; k < 16; k = k + 1) mem[k] = INITVAL[4 * k +: 4];
  end
  always @(posedge WCK) if (WRE) mem[WAD] <= DI;
  assign DO = mem[RAD];
endmodule
/* verilator lint_on UNUSEDPARAM */
