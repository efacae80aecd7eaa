//! Co-simulation of rust-hdl blocks against their generated Verilog.
//!
//! Every `rtl` block must simulate bit-exactly like the Verilog that
//! `generate_verilog` writes for it (`DESIGN.md` §4). This module is the
//! block-independent machinery for that check:
//!
//! 1. [`record`] drives a rust-hdl block directly (no threaded testbench) with
//!    a stimulus and records a [`Trace`]: per cycle, the input values and the
//!    sampled output values.
//! 2. Traces are written to and read from compact text vector files
//!    ([`Trace::write`], [`Trace::read`]; format below) that are committed in
//!    `vectors/`.
//! 3. [`run`] generates a Verilog testbench ([`testbench`]), runs the
//!    design on the trace's inputs under Icarus Verilog or Verilator and
//!    returns the outputs they sampled;
//!    [`compare`] checks them against the trace and names the first
//!    difference. [`check`] does both.
//! 4. [`lint_verilator`] runs `verilator --lint-only -Wall` and returns the
//!    parsed warnings; [`check_accepted`] fails on any warning whose code is
//!    not in an accepted list.
//!
//! # Cycle semantics
//!
//! The same in the Rust driver and in the testbench. Cycle `k`:
//! apply the inputs of cycle `k` while the clock is low, let the
//! combinational logic settle, **sample the outputs** (they are cycle `k`'s
//! outputs), raise the clock (state `k` → `k + 1`), lower it. So an output
//! that is a register shows in cycle `k` the value registered at the end of
//! cycle `k − 1`, and a combinational output shows its function of cycle
//! `k`'s inputs and state. State starts from the Verilog `initial` values
//! (rust-hdl's `DFF` initial values), so the block passed to [`record`] must
//! be freshly constructed, and the Verilog must come from another fresh
//! block ([`verilog_of`]). Nothing may be triggered by the falling edge.
//!
//! # Vector file format (version 1)
//!
//! Plain text, one line per cycle, diff-friendly:
//!
//! ```text
//! # cosim trace v1
//! inputs enable:1 data:8 threshold:8
//! outputs sum:8 above:1
//! cycles 5
//! 1 5 10 | 0 0
//! 1 7 10 | 5 0
//! 0 0 10 | c 0
//! *2
//! ```
//!
//! * Lines starting with `#` and blank lines are ignored (anywhere).
//! * `inputs` / `outputs` list the ports as `name:width` (width 1–64 bits),
//!   in the order of the values. `cycles N` gives the number of cycles after
//!   expansion; a truncated file is therefore detected.
//! * A data line holds the values in lowercase hexadecimal without leading
//!   zeros or `0x`, separated by single spaces, inputs then ` | ` then
//!   outputs. A file with only an `inputs` header (written by
//!   [`Trace::write_inputs`]) or only an `outputs` header
//!   ([`Trace::write_expected`]) has no `|`; [`Trace::read_split`] joins
//!   such a pair. One file per block trace is the normal case; the split form
//!   serves stimulus shared by several blocks or expected outputs kept apart.
//! * `*N` repeats the previous data line `N` more times (run-length coding of
//!   idle stretches, where neither inputs nor outputs change). Lines that
//!   differ are written plainly; typical traces take 20–40 bytes per cycle,
//!   so about 30 000 cycles (some image lines) fit in 1 MB.
//!
//! The testbench reads its own, simpler file (the number of cycles, then the
//! input values of one cycle per line) and writes the sampled outputs as
//! zero-padded hex, one cycle per line; both are internal to this module.
//!
//! # Tools
//!
//! Icarus Verilog 11 (`iverilog -g2012`, `vvp`) and Verilator 5.006
//! (`verilator --binary`, which needs `make` and `g++`). A missing tool is
//! the error [`CosimError::ToolMissing`], whose message gives the install
//! command; callers' tests therefore fail instead of passing silently.
//!
//! Verilator 5.006 does not re-evaluate combinational logic that reads a
//! variable written only by `$fscanf`; the testbench therefore scans into
//! temporaries and assigns the ports from them with blocking assignments.
//!
//! The machinery, one file per part, each using only those before it:
//! `error`, `trace`, `ports`, `record`, `compare`, `testbench`, `run`,
//! `vectors`, `lint`.

mod error;
mod trace;
mod ports;
mod record;
mod compare;
mod testbench;
mod run;
mod vectors;
mod lint;

pub use error::*;
pub use trace::*;
pub use ports::*;
pub use record::*;
pub use compare::*;
pub use run::*;
pub use vectors::*;
pub use lint::*;
