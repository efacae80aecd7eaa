//! The declivity tracker's window on the pixel stream: a shift register of
//! the last [`WINDOW_TAPS`] pixels with their flags and their line's values.
//!
//! The tracker examines the gradient of the pixel at the centre tap
//! ([`WINDOW_CENTER`]) and reads its neighbours `x ± 1`, `x ± 2` for the
//! attributes of paper §III; earlier taps feed its pipeline (`g`, `g²`,
//! `g²(2x+1)`). Tap k holds the pixel that entered k + 1 clocks ago.
//!
//! ## Ports
//! - In, every clock: `in_valid`, `in_first`, `in_last` (the pixel opens /
//!   closes its line), `in_pix`, `in_x`, and the line's `in_dt`, `in_thr`
//!   (`⌊d_t⌋`), `in_wide`, `in_sof`.
//! - Out: the taps the tracker reads, named by field and tap: `pix0..pix6`,
//!   `valid1`, `valid4`, `last1`, `last3`, `last4`, `first4`, `first5`,
//!   `x2`, `x4`, `dt4`, `thr2`, `wide4`, `sof4`.
//!
//! ## Timing
//! Shifts on every clock, bubbles (`in_valid` low) included; registered
//! outputs, all zero at start (Verilog initial values) and after `reset`
//! (synchronous, active high).
//!
//! No paper equation of its own: it feeds the tracker's eq. 2–3 and the
//! attributes of §III.
//!
//! Like rust-hdl's `DFF` and `RAM`, a primitive: the Rust model (`update`)
//! and the Verilog (`hdl`) describe the same shift register, held together
//! by the co-simulation tests, so that the simulation steps one block
//! instead of one generated flip-flop block per field and tap.

use crate::params::*;
use rust_hdl::prelude::*;

/// Taps of the window.
const WINDOW_TAPS: usize = 7;
/// The tap whose gradient is examined: `x + 1`, `x + 2` at taps 3 and 2,
/// `x - 1`, `x - 2` at taps 5 and 6.
pub(crate) const WINDOW_CENTER: usize = 4;

/// One tap's contents.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct Tap {
    valid: bool,
    first: bool,
    last: bool,
    pix: u64,
    x: u64,
    dt: u64,
    thr: u64,
    wide: bool,
    sof: bool,
}

#[derive(LogicBlock)]
pub(crate) struct PixelWindow {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset: every tap to zero.
    pub reset: Signal<In, Bit>,
    pub in_valid: Signal<In, Bit>,
    pub in_first: Signal<In, Bit>,
    pub in_last: Signal<In, Bit>,
    pub in_pix: Signal<In, Bits<PIXEL_BITS>>,
    pub in_x: Signal<In, Bits<X_BITS>>,
    pub in_dt: Signal<In, Bits<DT_BITS>>,
    pub in_thr: Signal<In, Bits<DT_INT_BITS>>,
    pub in_wide: Signal<In, Bit>,
    pub in_sof: Signal<In, Bit>,
    pub pix0: Signal<Out, Bits<PIXEL_BITS>>,
    pub pix1: Signal<Out, Bits<PIXEL_BITS>>,
    pub pix2: Signal<Out, Bits<PIXEL_BITS>>,
    pub pix3: Signal<Out, Bits<PIXEL_BITS>>,
    pub pix4: Signal<Out, Bits<PIXEL_BITS>>,
    pub pix5: Signal<Out, Bits<PIXEL_BITS>>,
    pub pix6: Signal<Out, Bits<PIXEL_BITS>>,
    pub valid1: Signal<Out, Bit>,
    pub valid4: Signal<Out, Bit>,
    pub last1: Signal<Out, Bit>,
    pub last3: Signal<Out, Bit>,
    pub last4: Signal<Out, Bit>,
    pub first4: Signal<Out, Bit>,
    pub first5: Signal<Out, Bit>,
    pub x2: Signal<Out, Bits<X_BITS>>,
    pub x4: Signal<Out, Bits<X_BITS>>,
    pub dt4: Signal<Out, Bits<DT_BITS>>,
    pub thr2: Signal<Out, Bits<DT_INT_BITS>>,
    pub wide4: Signal<Out, Bit>,
    pub sof4: Signal<Out, Bit>,
    _taps: [Tap; WINDOW_TAPS],
}

impl Default for PixelWindow {
    fn default() -> Self {
        Self {
            clock: Default::default(),
            reset: Default::default(),
            in_valid: Default::default(),
            in_first: Default::default(),
            in_last: Default::default(),
            in_pix: Default::default(),
            in_x: Default::default(),
            in_dt: Default::default(),
            in_thr: Default::default(),
            in_wide: Default::default(),
            in_sof: Default::default(),
            pix0: Default::default(),
            pix1: Default::default(),
            pix2: Default::default(),
            pix3: Default::default(),
            pix4: Default::default(),
            pix5: Default::default(),
            pix6: Default::default(),
            valid1: Default::default(),
            valid4: Default::default(),
            last1: Default::default(),
            last3: Default::default(),
            last4: Default::default(),
            first4: Default::default(),
            first5: Default::default(),
            x2: Default::default(),
            x4: Default::default(),
            dt4: Default::default(),
            thr2: Default::default(),
            wide4: Default::default(),
            sof4: Default::default(),
            _taps: [Tap::default(); WINDOW_TAPS],
        }
    }
}

impl Logic for PixelWindow {
    fn update(&mut self) {
        if !self.clock.pos_edge() {
            return;
        }
        self._taps.copy_within(0..WINDOW_TAPS - 1, 1);
        self._taps[0] = if self.reset.val() { Tap::default() } else { Tap {
            valid: self.in_valid.val(),
            first: self.in_first.val(),
            last: self.in_last.val(),
            pix: self.in_pix.val().to_u64(),
            x: self.in_x.val().to_u64(),
            dt: self.in_dt.val().to_u64(),
            thr: self.in_thr.val().to_u64(),
            wide: self.in_wide.val(),
            sof: self.in_sof.val(),
        } };
        if self.reset.val() {
            self._taps = [Tap::default(); WINDOW_TAPS];
        }
        let t = &self._taps;
        self.pix0.next = t[0].pix.into();
        self.pix1.next = t[1].pix.into();
        self.pix2.next = t[2].pix.into();
        self.pix3.next = t[3].pix.into();
        self.pix4.next = t[4].pix.into();
        self.pix5.next = t[5].pix.into();
        self.pix6.next = t[6].pix.into();
        self.valid1.next = t[1].valid;
        self.valid4.next = t[4].valid;
        self.last1.next = t[1].last;
        self.last3.next = t[3].last;
        self.last4.next = t[4].last;
        self.first4.next = t[4].first;
        self.first5.next = t[5].first;
        self.x2.next = t[2].x.into();
        self.x4.next = t[4].x.into();
        self.dt4.next = t[4].dt.into();
        self.thr2.next = t[2].thr.into();
        self.wide4.next = t[4].wide;
        self.sof4.next = t[4].sof;
    }

    fn connect(&mut self) {
        self.pix0.connect();
        self.pix1.connect();
        self.pix2.connect();
        self.pix3.connect();
        self.pix4.connect();
        self.pix5.connect();
        self.pix6.connect();
        self.valid1.connect();
        self.valid4.connect();
        self.last1.connect();
        self.last3.connect();
        self.last4.connect();
        self.first4.connect();
        self.first5.connect();
        self.x2.connect();
        self.x4.connect();
        self.dt4.connect();
        self.thr2.connect();
        self.wide4.connect();
        self.sof4.connect();
    }

    fn hdl(&self) -> Verilog {
        Verilog::Custom(window_verilog())
    }
}

/// The Verilog body of [`PixelWindow`]: each field shifts through as many
/// registers as its deepest tap read, the outputs being the last of them.
fn window_verilog() -> String {
    // (field, input, width, taps read)
    let fields: [(&str, &str, usize, &[usize]); 9] = [
        ("pix", "in_pix", PIXEL_BITS, &[0, 1, 2, 3, 4, 5, 6]),
        ("valid", "in_valid", 1, &[1, 4]),
        ("last", "in_last", 1, &[1, 3, 4]),
        ("first", "in_first", 1, &[4, 5]),
        ("x", "in_x", X_BITS, &[2, 4]),
        ("dt", "in_dt", DT_BITS, &[4]),
        ("thr", "in_thr", DT_INT_BITS, &[2]),
        ("wide", "in_wide", 1, &[4]),
        ("sof", "in_sof", 1, &[4]),
    ];
    let mut v = String::new();
    let mut shift = String::new();
    let mut init = String::new();
    for (name, input, width, taps) in fields {
        let deepest = *taps.iter().max().expect("a tap");
        let range = if width == 1 { String::new() } else { format!("[{}:0] ", width - 1) };
        // Taps that are outputs are the output registers themselves.
        let reg = |k: usize| if taps.contains(&k) { format!("{name}{k}") } else { format!("{name}_t{k}") };
        for k in 0..=deepest {
            if !taps.contains(&k) {
                v += &format!("reg {range}{name}_t{k};\n");
            }
            init += &format!("    {} = {width}'d0;\n", reg(k));
            let src = if k == 0 { input.to_string() } else { reg(k - 1) };
            shift += &format!("    {} <= {src};\n", reg(k));
        }
    }
    v += &format!("initial begin\n{init}end\n");
    let clear = init.replace(" = ", " <= ");
    v += &format!("always @(posedge clock) begin\n  if (reset) begin\n{clear}  end else begin\n{shift}  end\nend\n");
    v
}
