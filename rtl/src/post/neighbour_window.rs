//! One neighbour's window of the row check ([`crate::post::row_check`], whose
//! module doc describes the method): the row above or below the checked
//! row, read in order from its own copy of the row memory into a ring of
//! [`ROW_WINDOW`] slots, each held with its entry's bounds `X ± DX`,
//! `d ± DD`, and compared with the match the row check presents. The row
//! check has two, the same block twice.
//!
//! ## Ports
//! - `w_enable`, `w_address`, `w_data`: the loader's writes into this
//!   window's copy of the row memory (every copy takes every write).
//! - `start`: the engine starts a row; this window's row is in bank
//!   `bank` and has `count` entries (0 for no neighbour).
//! - `px`, `pd`: the presented match's bounds operands (the row check's
//!   compare stage, [`WIDE`] bits); `dvalid`: the decision stage holds the
//!   row's next undecided match.
//! - Out, for the decision stage: `found` (a held entry confirms the
//!   compared match), `crowd` (the window is full of entries none of which
//!   leaves, none right of the match's window, its row not all read and
//!   arrived: the match would wait for ever; the row check then counts the
//!   window complete, flagged, until the match is decided); and, for the
//!   match compared next, `complete` (the newest entry right of its
//!   window, or the row all read and arrived).
//!   (The decision, which depends on `found`, does not come back in:
//!   rust-hdl checks a block's outputs as if they depended on all of its
//!   inputs.)
//!
//! ## Timing
//! The comparisons with the match presented at clock `t` are registered
//! at `t + 1`, where `found` shows them (the decision stage). A read
//! issued at `t` lands in its slot at `t + 3` (the block RAM's address and
//! output registers); a read is issued while its slot, after the reads in
//! flight, is free, so the ring fills at one entry per clock. The ring
//! starts empty (Verilog initial values) and is emptied by `reset`
//! (synchronous, active high); `start` empties it for each row.
//!
//! No paper equation: part of golden's row check (`DESIGN.md` §2.2).

use crate::primitives::block_ram::BlockRam;
use crate::params::*;
use crate::post::row_check::WIDE;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

#[derive(LogicBlock)]
pub(crate) struct NeighbourWindow {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub w_enable: Signal<In, Bit>,
    pub w_address: Signal<In, Bits<ROW_ADDR_BITS>>,
    pub w_data: Signal<In, Bits<ROW_ENTRY_BITS>>,
    pub start: Signal<In, Bit>,
    pub bank: Signal<In, Bits<ROW_BANK_BITS>>,
    pub count: Signal<In, Bits<COUNT_BITS>>,
    pub px: Signal<In, Bits<WIDE>>,
    pub pd: Signal<In, Bits<WIDE>>,
    pub dvalid: Signal<In, Bit>,
    pub found: Signal<Out, Bit>,
    pub crowd: Signal<Out, Bit>,
    pub complete: Signal<Out, Bit>,
    mem: BlockRam<ROW_ENTRY_BITS, ROW_ADDR_BITS>,
    base: ResetDff<Bits<ROW_ADDR_BITS>>,
    rd: ResetDff<Bits<COUNT_BITS>>,
    // The row's entries not yet read; none (`rend`).
    rleft: ResetDff<Bits<COUNT_BITS>>,
    rend: ResetDff<Bit>,
    rd1: ResetDff<Bit>,
    rd2: ResetDff<Bit>,
    wi: ResetDff<Bits<ROW_WINDOW_BITS>>,
    wpos: ResetDff<Bits<ROW_WINDOW_BITS>>,
    // Each slot: held, and its entry's bounds `X + DX`, `X - DX`, `d + DD`,
    // `d - DD` (the last two modulo `2^WIDE`: see the comparisons); the
    // newest entry's `X - DX` (0 at a row's start).
    held: [ResetDff<Bit>; ROW_WINDOW],
    xp: [ResetDff<Bits<WIDE>>; ROW_WINDOW],
    xm: [ResetDff<Bits<WIDE>>; ROW_WINDOW],
    dp: [ResetDff<Bits<WIDE>>; ROW_WINDOW],
    dm: [ResetDff<Bits<WIDE>>; ROW_WINDOW],
    lxm: ResetDff<Bits<WIDE>>,
    // The comparisons with the presented match, registered: each slot left
    // of its window (`lt`), a confirming entry among slots 0-3 and 4-7
    // (`okq`); the window full, the newest entry right of it (`beyond`),
    // the row read and arrived (`loaded`).
    lt: [ResetDff<Bit>; ROW_WINDOW],
    okq: [ResetDff<Bit>; 2],
    full: ResetDff<Bit>,
    beyond: ResetDff<Bit>,
    loaded: ResetDff<Bit>,
    // The comparisons as differences whose top bit is the borrow: `X + DX
    // - x`, `x - (X - DX)`, `d_q - (d - DD)`, `d + DD - d_q` (negative:
    // left of the window, right of it, below it, above it).
    sl: [Signal<Local, Bits<WIDE>>; ROW_WINDOW],
    sg: [Signal<Local, Bits<WIDE>>; ROW_WINDOW],
    sdl: [Signal<Local, Bits<WIDE>>; ROW_WINDOW],
    sdh: [Signal<Local, Bits<WIDE>>; ROW_WINDOW],
    sb: Signal<Local, Bits<WIDE>>,
    okc: [Signal<Local, Bit>; ROW_WINDOW],
    stay: [Signal<Local, Bit>; ROW_WINDOW],
    rx: Signal<Local, Bits<POS_BITS>>,
    rdd: Signal<Local, Bits<POS_BITS>>,
    ex: Signal<Local, Bits<WIDE>>,
    ed: Signal<Local, Bits<WIDE>>,
    nxp: Signal<Local, Bits<WIDE>>,
    nxm: Signal<Local, Bits<WIDE>>,
    ndp: Signal<Local, Bits<WIDE>>,
    ndm: Signal<Local, Bits<WIDE>>,
    w_held: Signal<Local, Bit>,
    w_lt: Signal<Local, Bit>,
    slot_free: Signal<Local, Bit>,
    issue: Signal<Local, Bit>,
    // Some entry is left of the presented match's window (the OR of the
    // `lt` registers), a register of its own beside them: the crowded test
    // starts at registers, not two LUT levels of OR in front of the row
    // check's `both_ready`.
    anylt: ResetDff<Bit>,
    beyond_c: Signal<Local, Bit>,
    loaded_c: Signal<Local, Bit>,
    wslot: [Constant<Bits<ROW_WINDOW_BITS>>; ROW_WINDOW],
    dx: Constant<Bits<WIDE>>,
    dd: Constant<Bits<WIDE>>,
    ones: Constant<Bits<WIDE>>,
    count_one: Constant<Bits<COUNT_BITS>>,
    sign_at: Constant<Bits<8>>,
    index_bits: Constant<Bits<8>>,
    pos_bits: Constant<Bits<8>>,
}

impl Default for NeighbourWindow {
    fn default() -> Self {
        NeighbourWindow {
            clock: Default::default(),
            reset: Default::default(),
            w_enable: Default::default(),
            w_address: Default::default(),
            w_data: Default::default(),
            start: Default::default(),
            bank: Default::default(),
            count: Default::default(),
            px: Default::default(),
            pd: Default::default(),
            dvalid: Default::default(),
            found: Default::default(),
            crowd: Default::default(),
            complete: Default::default(),
            mem: Default::default(),
            base: Default::default(),
            rd: Default::default(),
            rleft: Default::default(),
            rend: Default::default(),
            rd1: Default::default(),
            rd2: Default::default(),
            wi: Default::default(),
            wpos: Default::default(),
            held: Default::default(),
            xp: Default::default(),
            xm: Default::default(),
            dp: Default::default(),
            dm: Default::default(),
            lxm: Default::default(),
            lt: Default::default(),
            okq: Default::default(),
            full: Default::default(),
            beyond: Default::default(),
            loaded: Default::default(),
            sl: Default::default(),
            sg: Default::default(),
            sdl: Default::default(),
            sdh: Default::default(),
            sb: Default::default(),
            okc: Default::default(),
            stay: Default::default(),
            rx: Default::default(),
            rdd: Default::default(),
            ex: Default::default(),
            ed: Default::default(),
            nxp: Default::default(),
            nxm: Default::default(),
            ndp: Default::default(),
            ndm: Default::default(),
            w_held: Default::default(),
            w_lt: Default::default(),
            slot_free: Default::default(),
            issue: Default::default(),
            anylt: Default::default(),
            beyond_c: Default::default(),
            loaded_c: Default::default(),
            wslot: core::array::from_fn(|i| Constant::new((i as u64).into())),
            dx: Constant::new(CONSISTENT_DX_LSB.into()),
            dd: Constant::new(CONSISTENT_DD_LSB.into()),
            ones: Constant::new(((1u64 << (WIDE - 1)) - 1).into()),
            count_one: Constant::new(1u64.into()),
            sign_at: Constant::new(((WIDE - 1) as u64).into()),
            index_bits: Constant::new((INDEX_BITS as u64).into()),
            pos_bits: Constant::new((POS_BITS as u64).into()),
        }
    }
}

impl Logic for NeighbourWindow {
    #[hdl_gen]
    fn update(&mut self) {
        dff_setup!(self, clock, base, rd, rleft, rend, rd1, rd2, wi, wpos, lxm, full, beyond, loaded, anylt);
        self.base.reset.next = self.reset.val();
        self.rd.reset.next = self.reset.val();
        self.rleft.reset.next = self.reset.val();
        self.rend.reset.next = self.reset.val();
        self.rd1.reset.next = self.reset.val();
        self.rd2.reset.next = self.reset.val();
        self.wi.reset.next = self.reset.val();
        self.wpos.reset.next = self.reset.val();
        self.lxm.reset.next = self.reset.val();
        self.full.reset.next = self.reset.val();
        self.beyond.reset.next = self.reset.val();
        self.loaded.reset.next = self.reset.val();
        self.anylt.reset.next = self.reset.val();
        // The memory copy takes the loader's writes.
        self.mem.clock.next = self.clock.val();
        self.mem.write_enable.next = self.w_enable.val();
        self.mem.write_address.next = self.w_address.val();
        self.mem.write_data.next = self.w_data.val();
        for i in 0..ROW_WINDOW {
            self.held[i].clock.next = self.clock.val();
            self.held[i].reset.next = self.reset.val();
            self.xp[i].clock.next = self.clock.val();
            self.xp[i].reset.next = self.reset.val();
            self.xm[i].clock.next = self.clock.val();
            self.xm[i].reset.next = self.reset.val();
            self.dp[i].clock.next = self.clock.val();
            self.dp[i].reset.next = self.reset.val();
            self.dm[i].clock.next = self.clock.val();
            self.dm[i].reset.next = self.reset.val();
            self.lt[i].clock.next = self.clock.val();
            self.lt[i].reset.next = self.reset.val();
            self.xp[i].d.next = self.xp[i].q.val();
            self.xm[i].d.next = self.xm[i].q.val();
            self.dp[i].d.next = self.dp[i].q.val();
            self.dm[i].d.next = self.dm[i].q.val();
        }
        // An arriving entry's bounds.
        self.rx.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.mem.read_data.val() >> self.pos_bits.val());
        self.rdd.next = bit_cast::<POS_BITS, ROW_ENTRY_BITS>(self.mem.read_data.val());
        self.ex.next = bit_cast::<WIDE, POS_BITS>(self.rx.val());
        self.ed.next = bit_cast::<WIDE, POS_BITS>(self.rdd.val());
        self.nxp.next = self.ex.val() + self.dx.val();
        // (`X - DX` and `d - DD` may wrap below zero: subtracted in its
        // comparison, such a bound never borrows, as if there were none.)
        self.nxm.next = self.ex.val() - self.dx.val();
        self.ndp.next = self.ed.val() + self.dd.val();
        self.ndm.next = self.ed.val() - self.dd.val();
        // The slots: a decided match's left entries leave (`lt` of the
        // match in the decision stage), the arriving read lands at `wi`.
        for i in 0..ROW_WINDOW {
            self.stay[i].next = self.held[i].q.val() & !(self.dvalid.val() & self.lt[i].q.val());
            self.held[i].d.next = self.stay[i].val();
            // A free slot's bounds fail every comparison (so that the
            // comparisons need not look at `held`).
            if !self.stay[i].val() {
                self.xp[i].d.next = self.ones.val();
                self.xm[i].d.next = self.ones.val();
            }
            if self.rd2.q.val() & (self.wi.q.val() == self.wslot[i].val()) {
                self.held[i].d.next = true;
                self.xp[i].d.next = self.nxp.val();
                self.xm[i].d.next = self.nxm.val();
                self.dp[i].d.next = self.ndp.val();
                self.dm[i].d.next = self.ndm.val();
            }
        }
        if self.rd2.q.val() {
            self.wi.d.next = self.wi.q.val() + 1;
            self.lxm.d.next = self.nxm.val();
        }
        // A read is issued while its slot (after the reads in flight, `wi +
        // rd1 + rd2`) is free, not held or leaving now: the held slots are
        // one run ending before `wi`. That slot is a register of its own,
        // `wpos`, which moves on with each read issued (`wi + rd2` is the
        // next `wi`, the read issued the next `rd1`, `rd1` the next `rd2`);
        // its flags are picked by it and the decision stage's `dvalid` comes
        // last, one LUT before the read's enables, not through the slots'
        // `stay` and a pick by `wi + rd1 + rd2`.
        self.w_held.next = false;
        self.w_lt.next = false;
        for i in 0..ROW_WINDOW {
            if self.wpos.q.val() == self.wslot[i].val() {
                self.w_held.next = self.held[i].q.val();
                self.w_lt.next = self.lt[i].q.val();
            }
        }
        self.slot_free.next = !self.w_held.val() | (self.dvalid.val() & self.w_lt.val());
        self.issue.next = !self.rend.q.val() & self.slot_free.val();
        self.rd1.d.next = self.issue.val();
        self.rd2.d.next = self.rd1.q.val();
        if self.issue.val() {
            self.wpos.d.next = self.wpos.q.val() + 1;
            self.rd.d.next = self.rd.q.val() + 1;
            self.rleft.d.next = self.rleft.q.val() - 1;
            self.rend.d.next = self.rleft.q.val() == self.count_one.val();
        }
        self.mem.read_address.next = self.base.q.val() + bit_cast::<ROW_ADDR_BITS, COUNT_BITS>(self.rd.q.val());
        // The comparisons with the presented match (registered; a free
        // slot, its position bounds all ones, is neither left of the window
        // nor confirming). Each is the borrow of a subtraction (one carry
        // chain).
        for i in 0..ROW_WINDOW {
            self.sl[i].next = self.xp[i].q.val() - self.px.val();
            self.sg[i].next = self.px.val() - self.xm[i].q.val();
            self.sdl[i].next = self.pd.val() - self.dm[i].q.val();
            self.sdh[i].next = self.dp[i].q.val() - self.pd.val();
            self.lt[i].d.next = self.sl[i].val().get_bit(self.sign_at.val().index());
            self.okc[i].next = !self.sl[i].val().get_bit(self.sign_at.val().index()) & !self.sg[i].val().get_bit(self.sign_at.val().index()) & !self.sdl[i].val().get_bit(self.sign_at.val().index()) & !self.sdh[i].val().get_bit(self.sign_at.val().index());
        }
        self.okq[0].clock.next = self.clock.val();
        self.okq[0].reset.next = self.reset.val();
        self.okq[1].clock.next = self.clock.val();
        self.okq[1].reset.next = self.reset.val();
        self.okq[0].d.next = self.okc[0].val() | self.okc[1].val() | self.okc[2].val() | self.okc[3].val();
        self.okq[1].d.next = self.okc[4].val() | self.okc[5].val() | self.okc[6].val() | self.okc[7].val();
        self.full.d.next = self.held[0].q.val() & self.held[1].q.val() & self.held[2].q.val() & self.held[3].q.val() & self.held[4].q.val() & self.held[5].q.val() & self.held[6].q.val() & self.held[7].q.val();
        self.sb.next = self.px.val() - self.lxm.q.val();
        // (The newest entry, once it has left, was left of an earlier
        // match's window, so never right of this one's.)
        self.beyond_c.next = self.sb.val().get_bit(self.sign_at.val().index());
        self.loaded_c.next = self.rend.q.val() & !self.rd1.q.val() & !self.rd2.q.val();
        self.beyond.d.next = self.beyond_c.val();
        self.loaded.d.next = self.loaded_c.val();
        // The decision stage's view: a confirming entry; crowded.
        self.found.next = self.okq[0].q.val() | self.okq[1].q.val();
        self.anylt.d.next = self.sl[0].val().get_bit(self.sign_at.val().index())
            | self.sl[1].val().get_bit(self.sign_at.val().index())
            | self.sl[2].val().get_bit(self.sign_at.val().index())
            | self.sl[3].val().get_bit(self.sign_at.val().index())
            | self.sl[4].val().get_bit(self.sign_at.val().index())
            | self.sl[5].val().get_bit(self.sign_at.val().index())
            | self.sl[6].val().get_bit(self.sign_at.val().index())
            | self.sl[7].val().get_bit(self.sign_at.val().index());
        self.crowd.next = self.dvalid.val() & self.full.q.val() & !self.anylt.q.val() & !self.beyond.q.val() & !self.loaded.q.val() & !self.found.val();
        self.complete.next = self.beyond_c.val() | self.loaded_c.val();
        // A row starts: this window's row from its first entry.
        if self.start.val() {
            self.base.d.next = bit_cast::<ROW_ADDR_BITS, ROW_BANK_BITS>(self.bank.val()) << self.index_bits.val();
            self.rleft.d.next = self.count.val();
            self.rd.d.next = 0.into();
            self.rend.d.next = !self.count.val().any();
            self.rd1.d.next = false;
            self.rd2.d.next = false;
            self.wi.d.next = 0.into();
            self.wpos.d.next = 0.into();
            self.lxm.d.next = 0.into();
            for i in 0..ROW_WINDOW {
                self.held[i].d.next = false;
            }
        }
    }
}
