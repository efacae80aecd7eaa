//! The blocks as Verilog: generation ([`verilog`]), the simulation models
//! of the ECP5 primitives it instantiates ([`primitives`]), a block as a
//! self-contained IP folder ([`ip`]), co-simulation
//! of the Verilog against the Rust model under Icarus and Verilator and
//! Verilator's lint ([`cosim`]), the traces each block's co-simulation
//! replays ([`traces`]), whole frames through the line processor's Verilog
//! ([`frame`]) and beat by beat from scripts that may break the stream's
//! rules ([`beats`]; the fault campaign, [`faults`]), synthesis for the ECP5 with Yosys and nextpnr ([`synth`])
//! and formal proofs with SymbiYosys ([`formal`]), each in a work directory
//! of its own ([`workdir`]).

pub(crate) mod workdir;
pub mod primitives;
pub mod verilog;
pub mod ip;
pub mod cosim;
pub mod traces;
pub mod frame;
pub mod beats;
pub mod faults;
pub mod synth;
pub mod formal;
