//! Memories, multipliers, the reset register and the reset buffer as ECP5 primitives or logic, each with a rust-hdl model for simulation.

pub mod block_ram;
pub mod lut_ram;
pub mod dsp_multiplier;
pub mod reset_register;
pub mod reset_buffer;
