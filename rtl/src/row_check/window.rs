//! One neighbouring row's window for the row check ([`super::RowCheck`]):
//! a copy of the row-check memory, read in order from the start of the
//! neighbouring row into a ring of [`ROW_WINDOW`] registers, compared in
//! one clock with the checked match.
//!
//! ## Ports
//! - Write side (driven alike for every copy): `w_en`, `w_addr` (bank,
//!   index), `w_data` (`X` above the disparity).
//! - `start` (a clock): a new checked row; the neighbour's matches are in
//!   bank `bank`, `count` of them (0: no neighbour). The ring empties and
//!   the reads start again at the bank's first match.
//! - The query: `q_valid`, `q_x` (`X` of the checked match), `q_d` (its
//!   disparity); `q_x` does not decrease within a row.
//! - `hit`: a ring entry lies within [`CONSISTENT_DX_LSB`] of `q_x` and its
//!   disparity within [`CONSISTENT_DD_LSB`] of `q_d` (both inclusive).
//!   `done`: the ring holds every match of the row up to `q_x + DX` (an
//!   entry right of the window is in it, or every match has arrived), so
//!   no `hit` means no confirmation from this row. `crowded`: the ring is
//!   full of matches inside the window without a hit: more than
//!   `ROW_WINDOW - 1` matches within 6 px (never with matches a pixel
//!   apart); the caller decides without the rest.
//!
//! ## Timing
//! Reads start the clock after `start`, one per clock while the ring and
//! the reads in flight leave a slot free; a read's entry is in the ring
//! three clocks after its address (the memory's two clocks, the ring's
//! write). Entries left of the window (`X_e < q_x - DX`, while `q_valid`)
//! leave the ring on the clock they are seen, all of them at once.

use crate::block_ram::BlockRam;
use crate::params::*;
use rust_hdl::prelude::*;

/// Bits of the position comparisons: a position plus a threshold.
const WIDE: usize = POS_BITS + 1;
/// Bits of the ring's fill `0 ..= ROW_WINDOW`.
const FILL_BITS: usize = ROW_WINDOW_BITS + 1;

#[derive(LogicBlock)]
pub struct RowWindow {
    pub clock: Signal<In, Clock>,
    pub w_en: Signal<In, Bit>,
    pub w_addr: Signal<In, Bits<ROW_ADDR_BITS>>,
    pub w_data: Signal<In, Bits<ROW_ENTRY_BITS>>,
    pub start: Signal<In, Bit>,
    pub bank: Signal<In, Bits<ROW_BANK_BITS>>,
    pub count: Signal<In, Bits<COUNT_BITS>>,
    pub q_valid: Signal<In, Bit>,
    pub q_x: Signal<In, Bits<POS_BITS>>,
    pub q_d: Signal<In, Bits<POS_BITS>>,
    pub hit: Signal<Out, Bit>,
    pub done: Signal<Out, Bit>,
    pub crowded: Signal<Out, Bit>,
    mem: BlockRam<ROW_ENTRY_BITS, ROW_ADDR_BITS>,
    // The row: its first address, its matches, the next read, the reads in
    // flight (one and two clocks old).
    base: DFF<Bits<ROW_ADDR_BITS>>,
    n: DFF<Bits<COUNT_BITS>>,
    rd: DFF<Bits<COUNT_BITS>>,
    rd1: DFF<Bit>,
    rd2: DFF<Bit>,
    // The ring: its first entry, the next write, the entries held.
    head: DFF<Bits<ROW_WINDOW_BITS>>,
    wi: DFF<Bits<ROW_WINDOW_BITS>>,
    fill: DFF<Bits<FILL_BITS>>,
    x0: DFF<Bits<POS_BITS>>,
    x1: DFF<Bits<POS_BITS>>,
    x2: DFF<Bits<POS_BITS>>,
    x3: DFF<Bits<POS_BITS>>,
    x4: DFF<Bits<POS_BITS>>,
    x5: DFF<Bits<POS_BITS>>,
    x6: DFF<Bits<POS_BITS>>,
    x7: DFF<Bits<POS_BITS>>,
    d0: DFF<Bits<POS_BITS>>,
    d1: DFF<Bits<POS_BITS>>,
    d2: DFF<Bits<POS_BITS>>,
    d3: DFF<Bits<POS_BITS>>,
    d4: DFF<Bits<POS_BITS>>,
    d5: DFF<Bits<POS_BITS>>,
    d6: DFF<Bits<POS_BITS>>,
    d7: DFF<Bits<POS_BITS>>,
    // ---- Locals: the window's bounds, then per slot: held, left of the
    // window, right of it, confirming; the popped count.
    qx: Signal<Local, Bits<WIDE>>,
    qx_hi: Signal<Local, Bits<WIDE>>,
    qx_lo: Signal<Local, Bits<WIDE>>,
    qd: Signal<Local, Bits<WIDE>>,
    qd_hi: Signal<Local, Bits<WIDE>>,
    qd_lo: Signal<Local, Bits<WIDE>>,
    any_left: Signal<Local, Bit>,
    r0: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    v0: Signal<Local, Bit>,
    ex0: Signal<Local, Bits<WIDE>>,
    ed0: Signal<Local, Bits<WIDE>>,
    lt0: Signal<Local, Bit>,
    gt0: Signal<Local, Bit>,
    ok0: Signal<Local, Bit>,
    p0: Signal<Local, Bits<FILL_BITS>>,
    r1: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    v1: Signal<Local, Bit>,
    ex1: Signal<Local, Bits<WIDE>>,
    ed1: Signal<Local, Bits<WIDE>>,
    lt1: Signal<Local, Bit>,
    gt1: Signal<Local, Bit>,
    ok1: Signal<Local, Bit>,
    p1: Signal<Local, Bits<FILL_BITS>>,
    r2: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    v2: Signal<Local, Bit>,
    ex2: Signal<Local, Bits<WIDE>>,
    ed2: Signal<Local, Bits<WIDE>>,
    lt2: Signal<Local, Bit>,
    gt2: Signal<Local, Bit>,
    ok2: Signal<Local, Bit>,
    p2: Signal<Local, Bits<FILL_BITS>>,
    r3: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    v3: Signal<Local, Bit>,
    ex3: Signal<Local, Bits<WIDE>>,
    ed3: Signal<Local, Bits<WIDE>>,
    lt3: Signal<Local, Bit>,
    gt3: Signal<Local, Bit>,
    ok3: Signal<Local, Bit>,
    p3: Signal<Local, Bits<FILL_BITS>>,
    r4: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    v4: Signal<Local, Bit>,
    ex4: Signal<Local, Bits<WIDE>>,
    ed4: Signal<Local, Bits<WIDE>>,
    lt4: Signal<Local, Bit>,
    gt4: Signal<Local, Bit>,
    ok4: Signal<Local, Bit>,
    p4: Signal<Local, Bits<FILL_BITS>>,
    r5: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    v5: Signal<Local, Bit>,
    ex5: Signal<Local, Bits<WIDE>>,
    ed5: Signal<Local, Bits<WIDE>>,
    lt5: Signal<Local, Bit>,
    gt5: Signal<Local, Bit>,
    ok5: Signal<Local, Bit>,
    p5: Signal<Local, Bits<FILL_BITS>>,
    r6: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    v6: Signal<Local, Bit>,
    ex6: Signal<Local, Bits<WIDE>>,
    ed6: Signal<Local, Bits<WIDE>>,
    lt6: Signal<Local, Bit>,
    gt6: Signal<Local, Bit>,
    ok6: Signal<Local, Bit>,
    p6: Signal<Local, Bits<FILL_BITS>>,
    r7: Signal<Local, Bits<ROW_WINDOW_BITS>>,
    v7: Signal<Local, Bit>,
    ex7: Signal<Local, Bits<WIDE>>,
    ed7: Signal<Local, Bits<WIDE>>,
    lt7: Signal<Local, Bit>,
    gt7: Signal<Local, Bit>,
    ok7: Signal<Local, Bit>,
    p7: Signal<Local, Bits<FILL_BITS>>,
    beyond: Signal<Local, Bit>,
    found: Signal<Local, Bit>,
    npop: Signal<Local, Bits<FILL_BITS>>,
    kept: Signal<Local, Bits<FILL_BITS>>,
    occ: Signal<Local, Bits<FILL_BITS>>,
    loaded: Signal<Local, Bit>,
    issue: Signal<Local, Bit>,
    rx: Signal<Local, Bits<POS_BITS>>,
    rdd: Signal<Local, Bits<POS_BITS>>,
    // ---- Constants.
    slot0: Constant<Bits<ROW_WINDOW_BITS>>,
    slot1: Constant<Bits<ROW_WINDOW_BITS>>,
    slot2: Constant<Bits<ROW_WINDOW_BITS>>,
    slot3: Constant<Bits<ROW_WINDOW_BITS>>,
    slot4: Constant<Bits<ROW_WINDOW_BITS>>,
    slot5: Constant<Bits<ROW_WINDOW_BITS>>,
    slot6: Constant<Bits<ROW_WINDOW_BITS>>,
    slot7: Constant<Bits<ROW_WINDOW_BITS>>,
    dx: Constant<Bits<WIDE>>,
    dd: Constant<Bits<WIDE>>,
    one: Constant<Bits<FILL_BITS>>,
    ring_size: Constant<Bits<FILL_BITS>>,
    index_bits: Constant<Bits<8>>,
    pos_bits: Constant<Bits<8>>,
}

impl Default for RowWindow {
    fn default() -> Self {
        let slot = |k: u64| Constant::<Bits<ROW_WINDOW_BITS>>::new(k.into());
        RowWindow {
            clock: Default::default(),
            w_en: Default::default(),
            w_addr: Default::default(),
            w_data: Default::default(),
            start: Default::default(),
            bank: Default::default(),
            count: Default::default(),
            q_valid: Default::default(),
            q_x: Default::default(),
            q_d: Default::default(),
            hit: Default::default(),
            done: Default::default(),
            crowded: Default::default(),
            mem: Default::default(),
            base: Default::default(),
            n: Default::default(),
            rd: Default::default(),
            rd1: Default::default(),
            rd2: Default::default(),
            head: Default::default(),
            wi: Default::default(),
            fill: Default::default(),
            x0: Default::default(),
            x1: Default::default(),
            x2: Default::default(),
            x3: Default::default(),
            x4: Default::default(),
            x5: Default::default(),
            x6: Default::default(),
            x7: Default::default(),
            d0: Default::default(),
            d1: Default::default(),
            d2: Default::default(),
            d3: Default::default(),
            d4: Default::default(),
            d5: Default::default(),
            d6: Default::default(),
            d7: Default::default(),
            qx: Default::default(),
            qx_hi: Default::default(),
            qx_lo: Default::default(),
            qd: Default::default(),
            qd_hi: Default::default(),
            qd_lo: Default::default(),
            any_left: Default::default(),
            r0: Default::default(),
            v0: Default::default(),
            ex0: Default::default(),
            ed0: Default::default(),
            lt0: Default::default(),
            gt0: Default::default(),
            ok0: Default::default(),
            p0: Default::default(),
            r1: Default::default(),
            v1: Default::default(),
            ex1: Default::default(),
            ed1: Default::default(),
            lt1: Default::default(),
            gt1: Default::default(),
            ok1: Default::default(),
            p1: Default::default(),
            r2: Default::default(),
            v2: Default::default(),
            ex2: Default::default(),
            ed2: Default::default(),
            lt2: Default::default(),
            gt2: Default::default(),
            ok2: Default::default(),
            p2: Default::default(),
            r3: Default::default(),
            v3: Default::default(),
            ex3: Default::default(),
            ed3: Default::default(),
            lt3: Default::default(),
            gt3: Default::default(),
            ok3: Default::default(),
            p3: Default::default(),
            r4: Default::default(),
            v4: Default::default(),
            ex4: Default::default(),
            ed4: Default::default(),
            lt4: Default::default(),
            gt4: Default::default(),
            ok4: Default::default(),
            p4: Default::default(),
            r5: Default::default(),
            v5: Default::default(),
            ex5: Default::default(),
            ed5: Default::default(),
            lt5: Default::default(),
            gt5: Default::default(),
            ok5: Default::default(),
            p5: Default::default(),
            r6: Default::default(),
            v6: Default::default(),
            ex6: Default::default(),
            ed6: Default::default(),
            lt6: Default::default(),
            gt6: Default::default(),
            ok6: Default::default(),
            p6: Default::default(),
            r7: Default::default(),
            v7: Default::default(),
            ex7: Default::default(),
            ed7: Default::default(),
            lt7: Default::default(),
            gt7: Default::default(),
            ok7: Default::default(),
            p7: Default::default(),
            beyond: Default::default(),
            found: Default::default(),
            npop: Default::default(),
            kept: Default::default(),
            occ: Default::default(),
            loaded: Default::default(),
            issue: Default::default(),
            rx: Default::default(),
            rdd: Default::default(),
            slot0: slot(0),
            slot1: slot(1),
            slot2: slot(2),
            slot3: slot(3),
            slot4: slot(4),
            slot5: slot(5),
            slot6: slot(6),
            slot7: slot(7),
            dx: Constant::new(CONSISTENT_DX_LSB.into()),
            dd: Constant::new(CONSISTENT_DD_LSB.into()),
            one: Constant::new(1u64.into()),
            ring_size: Constant::new((ROW_WINDOW as u64).into()),
            index_bits: Constant::new((INDEX_BITS as u64).into()),
            pos_bits: Constant::new((POS_BITS as u64).into()),
        }
    }
}

impl Logic for RowWindow {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, base, n, rd, rd1, rd2, head, wi, fill, x0, x1, x2, x3, x4, x5, x6, x7, d0, d1, d2, d3, d4, d5, d6, d7);
        self.mem.clock.next = self.clock.val();
        self.mem.write_enable.next = self.w_en.val();
        self.mem.write_address.next = self.w_addr.val();
        self.mem.write_data.next = self.w_data.val();
        // The window's bounds: [q_x - DX, q_x + DX] (no left bound below DX),
        // [q_d - DD, q_d + DD] (from 0 below DD), one bit wider than a
        // position.
        self.qx.next = bit_cast::<WIDE, POS_BITS>(self.q_x.val());
        self.qd.next = bit_cast::<WIDE, POS_BITS>(self.q_d.val());
        self.qx_hi.next = self.qx.val() + self.dx.val();
        self.qd_hi.next = self.qd.val() + self.dd.val();
        self.any_left.next = self.q_valid.val() & (self.qx.val() >= self.dx.val());
        self.qx_lo.next = self.qx.val() - self.dx.val();
        self.qd_lo.next = 0.into();
        if self.qd.val() >= self.dd.val() {
            self.qd_lo.next = self.qd.val() - self.dd.val();
        }
        // Each slot: held (its place after the head below the fill), left
        // of the window (popped), right of it, confirming.
        self.r0.next = self.slot0.val() - self.head.q.val();
        self.v0.next = bit_cast::<FILL_BITS, ROW_WINDOW_BITS>(self.r0.val()) < self.fill.q.val();
        self.ex0.next = bit_cast::<WIDE, POS_BITS>(self.x0.q.val());
        self.ed0.next = bit_cast::<WIDE, POS_BITS>(self.d0.q.val());
        self.lt0.next = self.v0.val() & self.any_left.val() & (self.ex0.val() < self.qx_lo.val());
        self.gt0.next = self.v0.val() & (self.ex0.val() > self.qx_hi.val());
        self.ok0.next = self.v0.val() & !self.lt0.val() & !self.gt0.val() & (self.ed0.val() >= self.qd_lo.val()) & (self.ed0.val() <= self.qd_hi.val());
        self.p0.next = 0.into();
        if self.lt0.val() {
            self.p0.next = self.one.val();
        }
        self.r1.next = self.slot1.val() - self.head.q.val();
        self.v1.next = bit_cast::<FILL_BITS, ROW_WINDOW_BITS>(self.r1.val()) < self.fill.q.val();
        self.ex1.next = bit_cast::<WIDE, POS_BITS>(self.x1.q.val());
        self.ed1.next = bit_cast::<WIDE, POS_BITS>(self.d1.q.val());
        self.lt1.next = self.v1.val() & self.any_left.val() & (self.ex1.val() < self.qx_lo.val());
        self.gt1.next = self.v1.val() & (self.ex1.val() > self.qx_hi.val());
        self.ok1.next = self.v1.val() & !self.lt1.val() & !self.gt1.val() & (self.ed1.val() >= self.qd_lo.val()) & (self.ed1.val() <= self.qd_hi.val());
        self.p1.next = 0.into();
        if self.lt1.val() {
            self.p1.next = self.one.val();
        }
        self.r2.next = self.slot2.val() - self.head.q.val();
        self.v2.next = bit_cast::<FILL_BITS, ROW_WINDOW_BITS>(self.r2.val()) < self.fill.q.val();
        self.ex2.next = bit_cast::<WIDE, POS_BITS>(self.x2.q.val());
        self.ed2.next = bit_cast::<WIDE, POS_BITS>(self.d2.q.val());
        self.lt2.next = self.v2.val() & self.any_left.val() & (self.ex2.val() < self.qx_lo.val());
        self.gt2.next = self.v2.val() & (self.ex2.val() > self.qx_hi.val());
        self.ok2.next = self.v2.val() & !self.lt2.val() & !self.gt2.val() & (self.ed2.val() >= self.qd_lo.val()) & (self.ed2.val() <= self.qd_hi.val());
        self.p2.next = 0.into();
        if self.lt2.val() {
            self.p2.next = self.one.val();
        }
        self.r3.next = self.slot3.val() - self.head.q.val();
        self.v3.next = bit_cast::<FILL_BITS, ROW_WINDOW_BITS>(self.r3.val()) < self.fill.q.val();
        self.ex3.next = bit_cast::<WIDE, POS_BITS>(self.x3.q.val());
        self.ed3.next = bit_cast::<WIDE, POS_BITS>(self.d3.q.val());
        self.lt3.next = self.v3.val() & self.any_left.val() & (self.ex3.val() < self.qx_lo.val());
        self.gt3.next = self.v3.val() & (self.ex3.val() > self.qx_hi.val());
        self.ok3.next = self.v3.val() & !self.lt3.val() & !self.gt3.val() & (self.ed3.val() >= self.qd_lo.val()) & (self.ed3.val() <= self.qd_hi.val());
        self.p3.next = 0.into();
        if self.lt3.val() {
            self.p3.next = self.one.val();
        }
        self.r4.next = self.slot4.val() - self.head.q.val();
        self.v4.next = bit_cast::<FILL_BITS, ROW_WINDOW_BITS>(self.r4.val()) < self.fill.q.val();
        self.ex4.next = bit_cast::<WIDE, POS_BITS>(self.x4.q.val());
        self.ed4.next = bit_cast::<WIDE, POS_BITS>(self.d4.q.val());
        self.lt4.next = self.v4.val() & self.any_left.val() & (self.ex4.val() < self.qx_lo.val());
        self.gt4.next = self.v4.val() & (self.ex4.val() > self.qx_hi.val());
        self.ok4.next = self.v4.val() & !self.lt4.val() & !self.gt4.val() & (self.ed4.val() >= self.qd_lo.val()) & (self.ed4.val() <= self.qd_hi.val());
        self.p4.next = 0.into();
        if self.lt4.val() {
            self.p4.next = self.one.val();
        }
        self.r5.next = self.slot5.val() - self.head.q.val();
        self.v5.next = bit_cast::<FILL_BITS, ROW_WINDOW_BITS>(self.r5.val()) < self.fill.q.val();
        self.ex5.next = bit_cast::<WIDE, POS_BITS>(self.x5.q.val());
        self.ed5.next = bit_cast::<WIDE, POS_BITS>(self.d5.q.val());
        self.lt5.next = self.v5.val() & self.any_left.val() & (self.ex5.val() < self.qx_lo.val());
        self.gt5.next = self.v5.val() & (self.ex5.val() > self.qx_hi.val());
        self.ok5.next = self.v5.val() & !self.lt5.val() & !self.gt5.val() & (self.ed5.val() >= self.qd_lo.val()) & (self.ed5.val() <= self.qd_hi.val());
        self.p5.next = 0.into();
        if self.lt5.val() {
            self.p5.next = self.one.val();
        }
        self.r6.next = self.slot6.val() - self.head.q.val();
        self.v6.next = bit_cast::<FILL_BITS, ROW_WINDOW_BITS>(self.r6.val()) < self.fill.q.val();
        self.ex6.next = bit_cast::<WIDE, POS_BITS>(self.x6.q.val());
        self.ed6.next = bit_cast::<WIDE, POS_BITS>(self.d6.q.val());
        self.lt6.next = self.v6.val() & self.any_left.val() & (self.ex6.val() < self.qx_lo.val());
        self.gt6.next = self.v6.val() & (self.ex6.val() > self.qx_hi.val());
        self.ok6.next = self.v6.val() & !self.lt6.val() & !self.gt6.val() & (self.ed6.val() >= self.qd_lo.val()) & (self.ed6.val() <= self.qd_hi.val());
        self.p6.next = 0.into();
        if self.lt6.val() {
            self.p6.next = self.one.val();
        }
        self.r7.next = self.slot7.val() - self.head.q.val();
        self.v7.next = bit_cast::<FILL_BITS, ROW_WINDOW_BITS>(self.r7.val()) < self.fill.q.val();
        self.ex7.next = bit_cast::<WIDE, POS_BITS>(self.x7.q.val());
        self.ed7.next = bit_cast::<WIDE, POS_BITS>(self.d7.q.val());
        self.lt7.next = self.v7.val() & self.any_left.val() & (self.ex7.val() < self.qx_lo.val());
        self.gt7.next = self.v7.val() & (self.ex7.val() > self.qx_hi.val());
        self.ok7.next = self.v7.val() & !self.lt7.val() & !self.gt7.val() & (self.ed7.val() >= self.qd_lo.val()) & (self.ed7.val() <= self.qd_hi.val());
        self.p7.next = 0.into();
        if self.lt7.val() {
            self.p7.next = self.one.val();
        }
        self.beyond.next = self.gt0.val() | self.gt1.val() | self.gt2.val() | self.gt3.val() | self.gt4.val() | self.gt5.val() | self.gt6.val() | self.gt7.val();
        self.found.next = self.q_valid.val() & (self.ok0.val() | self.ok1.val() | self.ok2.val() | self.ok3.val() | self.ok4.val() | self.ok5.val() | self.ok6.val() | self.ok7.val());
        self.npop.next = self.p0.val() + self.p1.val() + self.p2.val() + self.p3.val() + self.p4.val() + self.p5.val() + self.p6.val() + self.p7.val();
        // Every match of the row read and arrived.
        self.loaded.next = (self.rd.q.val() == self.n.q.val()) & !self.rd1.q.val() & !self.rd2.q.val();
        self.hit.next = self.found.val();
        self.done.next = self.beyond.val() | self.loaded.val();
        self.crowded.next = (self.fill.q.val() == self.ring_size.val()) & !self.npop.val().any() & !self.beyond.val() & !self.found.val() & !self.loaded.val();
        // The ring: pops at the head, the arriving read at `wi`; a read is
        // issued while the entries kept and in flight leave a slot free.
        self.kept.next = self.fill.q.val() - self.npop.val();
        self.head.d.next = self.head.q.val() + bit_cast::<ROW_WINDOW_BITS, FILL_BITS>(self.npop.val());
        self.occ.next = self.kept.val();
        if self.rd1.q.val() {
            self.occ.next = self.kept.val() + self.one.val();
        }
        self.fill.d.next = self.kept.val();
        if self.rd2.q.val() {
            self.fill.d.next = self.kept.val() + self.one.val();
            self.occ.next = self.kept.val() + self.one.val();
            if self.rd1.q.val() {
                self.occ.next = self.kept.val() + self.one.val() + self.one.val();
            }
            self.wi.d.next = self.wi.q.val() + 1;
        }
        self.issue.next = (self.rd.q.val() != self.n.q.val()) & (self.occ.val() < self.ring_size.val());
        self.rd1.d.next = self.issue.val();
        self.rd2.d.next = self.rd1.q.val();
        if self.issue.val() {
            self.rd.d.next = self.rd.q.val() + 1;
        }
        self.mem.read_address.next = self.base.q.val() + bit_cast::<ROW_ADDR_BITS, COUNT_BITS>(self.rd.q.val());
        self.rx.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.mem.read_data.val() >> self.pos_bits.val());
        self.rdd.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.mem.read_data.val());
        if self.rd2.q.val() & (self.wi.q.val() == self.slot0.val()) {
            self.x0.d.next = self.rx.val();
            self.d0.d.next = self.rdd.val();
        }
        if self.rd2.q.val() & (self.wi.q.val() == self.slot1.val()) {
            self.x1.d.next = self.rx.val();
            self.d1.d.next = self.rdd.val();
        }
        if self.rd2.q.val() & (self.wi.q.val() == self.slot2.val()) {
            self.x2.d.next = self.rx.val();
            self.d2.d.next = self.rdd.val();
        }
        if self.rd2.q.val() & (self.wi.q.val() == self.slot3.val()) {
            self.x3.d.next = self.rx.val();
            self.d3.d.next = self.rdd.val();
        }
        if self.rd2.q.val() & (self.wi.q.val() == self.slot4.val()) {
            self.x4.d.next = self.rx.val();
            self.d4.d.next = self.rdd.val();
        }
        if self.rd2.q.val() & (self.wi.q.val() == self.slot5.val()) {
            self.x5.d.next = self.rx.val();
            self.d5.d.next = self.rdd.val();
        }
        if self.rd2.q.val() & (self.wi.q.val() == self.slot6.val()) {
            self.x6.d.next = self.rx.val();
            self.d6.d.next = self.rdd.val();
        }
        if self.rd2.q.val() & (self.wi.q.val() == self.slot7.val()) {
            self.x7.d.next = self.rx.val();
            self.d7.d.next = self.rdd.val();
        }
        // A new row: the ring empties, the reads in flight are forgotten.
        if self.start.val() {
            self.base.d.next = bit_cast::<ROW_ADDR_BITS, ROW_BANK_BITS>(self.bank.val()) << self.index_bits.val();
            self.n.d.next = self.count.val();
            self.rd.d.next = 0.into();
            self.rd1.d.next = false;
            self.rd2.d.next = false;
            self.head.d.next = 0.into();
            self.wi.d.next = 0.into();
            self.fill.d.next = 0.into();
        }
    }
}
