// The modules of the line processor, built once per configuration: this
// crate includes them with `sd`'s sizes, `rtl-hd` with `hd`'s
// (`crate::config`; every width derives from it in `crate::params`).

pub mod params;
pub mod stream;
pub mod detector;
pub mod matcher;
pub mod post;
pub mod primitives;
pub mod stereo_line_processor;

pub use rust_hdl;

/// One clock of a block under direct drive in the unit tests: rising edge,
/// settle, falling edge, settle.
#[cfg(test)]
pub(crate) fn tick<B: rust_hdl::prelude::Block>(uut: &mut B, clock: fn(&mut B) -> &mut rust_hdl::prelude::Signal<rust_hdl::prelude::In, rust_hdl::prelude::Clock>) {
    use rust_hdl::prelude::*;
    clock(uut).next = Clock::from(true);
    assert!(simulate(uut, 100), "settles");
    clock(uut).next = Clock::from(false);
    assert!(simulate(uut, 100), "settles");
}
