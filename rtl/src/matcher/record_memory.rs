//! One view's declivity records for the matcher: two lines' worth (two
//! banks of `N_MAX` entries, the bank bit above the index), each record's
//! six neighbour levels put into the gain rule's format on the way in; and
//! a copy of the positions of four lines (four banks: the traceback of a
//! line reads its positions while the next line's sweep reads the records
//! and the one after loads).
//!
//! ## Ports
//! - `relative`: the gain rule (a design constant of the matcher): levels
//!   `2·I - e + LEVEL_OFFSET` with `e = I(x_i) + I(x_{i+1})`, the
//!   declivity's end-level sum, when set; `2·I + LEVEL_OFFSET` otherwise
//!   (paper §III, eq. 4–5, and `golden::gain::Neighbours`).
//! - Write: `w_enable`, `w_addr` (the line's bank in the position copy's
//!   four, then the index: the records' bank is its low bit), and the
//!   record as the detector sends it:
//!   `w_pos`, `w_amp` (only its sign is kept: the polarity), `w_left0..2`,
//!   `w_right0..2`.
//! - Read: `r_addr`; two clocks later `pos`, `lev0..5` (left 0–2, then
//!   right 0–2) and `rising`. Read of the position copy: `p_addr`; two
//!   clocks later `p_pos`.
//!
//! ## Timing
//! One write and one read per clock (block RAMs with their output
//! registers, [`BlockRam`]: a read takes two clocks). A write reaches the
//! RAM [`WRITE_LAG`] = 4 clocks after it is on the ports: the record is
//! registered as it comes, then with the end-level sum `e` (one adder),
//! then each level `(2·I + LEVEL_OFFSET) - e` (one subtractor: `2·I` is
//! below `LEVEL_OFFSET`, a power of two, so `2·I + LEVEL_OFFSET` is wiring),
//! then once more as it is, beside the RAM, so that the route from the
//! matcher's input register, the conversion's two adders in series, the
//! route from the record memory's first register into them, and the route
//! from them to the block RAM's data inputs each have a clock of their own
//! on a full device. The matcher never reads an
//! address on the clock it writes it (the loader writes one bank while the
//! engine reads the other, and a pair's last record is in the RAM before
//! the engine's first read of it: see
//! [`crate::matcher::declivity_matcher::TAKE_AFTER_MARKER`]), and its Verilog tells
//! the synthesis so (`no_rw_check`): what such a read returns is left
//! undefined. `w_enable` low writes nothing. The RAMs and
//! registers start from their Verilog initial values (zero); `reset`
//! (synchronous, active high) returns the registers there, and the RAMs need
//! none: the matcher reads only entries it has written.

use crate::primitives::block_ram::BlockRam;
use crate::params::*;
use crate::primitives::reset_register::ResetDff;
use rust_hdl::prelude::*;

/// Clocks from a write on the ports (`w_enable` high) to the clock it is on
/// the block RAMs' write ports (written at that clock's end): the record as
/// it comes, the end-level sum, the levels, the register beside the RAMs.
pub(crate) const WRITE_LAG: usize = 4;
/// Grey levels a record carries: three on each side of the declivity.
const LEVELS: usize = 6;
/// Address bits of the position copy: four banks of `N_MAX` positions.
pub const COPY_ADDR_BITS: usize = INDEX_BITS + 2;

#[derive(LogicBlock)]
pub(crate) struct RecordMemory {
    pub clock: Signal<In, Clock>,
    /// Synchronous, active-high reset.
    pub reset: Signal<In, Bit>,
    pub relative: Signal<In, Bit>,
    pub w_enable: Signal<In, Bit>,
    pub w_addr: Signal<In, Bits<COPY_ADDR_BITS>>,
    pub w_pos: Signal<In, Bits<POS_BITS>>,
    pub w_amp: Signal<In, Bits<AMP_BITS>>,
    pub w_left0: Signal<In, Bits<PIXEL_BITS>>,
    pub w_left1: Signal<In, Bits<PIXEL_BITS>>,
    pub w_left2: Signal<In, Bits<PIXEL_BITS>>,
    pub w_right0: Signal<In, Bits<PIXEL_BITS>>,
    pub w_right1: Signal<In, Bits<PIXEL_BITS>>,
    pub w_right2: Signal<In, Bits<PIXEL_BITS>>,
    pub r_addr: Signal<In, Bits<DIAG_BITS>>,
    pub pos: Signal<Out, Bits<POS_BITS>>,
    pub lev0: Signal<Out, Bits<LEVEL_BITS>>,
    pub lev1: Signal<Out, Bits<LEVEL_BITS>>,
    pub lev2: Signal<Out, Bits<LEVEL_BITS>>,
    pub lev3: Signal<Out, Bits<LEVEL_BITS>>,
    pub lev4: Signal<Out, Bits<LEVEL_BITS>>,
    pub lev5: Signal<Out, Bits<LEVEL_BITS>>,
    pub rising: Signal<Out, Bit>,
    pub p_addr: Signal<In, Bits<COPY_ADDR_BITS>>,
    pub p_pos: Signal<Out, Bits<POS_BITS>>,
    // The position with the polarity above it (one block RAM, not a
    // 1-bit LUT RAM whose read would sit on the address path).
    pos_mem: BlockRam<{ POS_BITS + 1 }, DIAG_BITS>,
    lev_mem: [BlockRam<LEVEL_BITS, DIAG_BITS>; LEVELS],
    pos_copy: BlockRam<POS_BITS, COPY_ADDR_BITS>,
    // The write as it comes.
    wi_enable: ResetDff<Bit>,
    wi_addr: ResetDff<Bits<COPY_ADDR_BITS>>,
    wi_pos: ResetDff<Bits<POS_BITS>>,
    wi_falling: ResetDff<Bit>,
    // The grey levels in the order of `lev0..5`: left 0–2, then right 0–2.
    wi_lev: [ResetDff<Bits<PIXEL_BITS>>; LEVELS],
    // The write with the end-level sum `e`.
    wb_enable: ResetDff<Bit>,
    wb_addr: ResetDff<Bits<COPY_ADDR_BITS>>,
    wb_pos: ResetDff<Bits<{ POS_BITS + 1 }>>,
    wb_ends: ResetDff<Bits<LEVEL_BITS>>,
    wb_lev: [ResetDff<Bits<PIXEL_BITS>>; LEVELS],
    // The write in the RAMs' format.
    wc_enable: ResetDff<Bit>,
    wc_addr: ResetDff<Bits<COPY_ADDR_BITS>>,
    wc_pos: ResetDff<Bits<{ POS_BITS + 1 }>>,
    wc_lev: [ResetDff<Bits<LEVEL_BITS>>; LEVELS],
    // The same, beside the RAMs.
    wq_enable: ResetDff<Bit>,
    wq_addr: ResetDff<Bits<COPY_ADDR_BITS>>,
    wq_pos: ResetDff<Bits<{ POS_BITS + 1 }>>,
    wq_lev: [ResetDff<Bits<LEVEL_BITS>>; LEVELS],
    ends: Signal<Local, Bits<LEVEL_BITS>>,
    lev_off: [Signal<Local, Bits<LEVEL_BITS>>; LEVELS],
    level_offset: Constant<Bits<LEVEL_BITS>>,
    amp_msb: Constant<Bits<8>>,
    rise_bit: Constant<Bits<8>>,
    bit0: Constant<Bits<8>>,
    one: Constant<Bits<LEVEL_BITS>>,
}

impl Default for RecordMemory {
    fn default() -> Self {
        RecordMemory {
            clock: Default::default(),
            reset: Default::default(),
            relative: Default::default(),
            w_enable: Default::default(),
            w_addr: Default::default(),
            w_pos: Default::default(),
            w_amp: Default::default(),
            w_left0: Default::default(),
            w_left1: Default::default(),
            w_left2: Default::default(),
            w_right0: Default::default(),
            w_right1: Default::default(),
            w_right2: Default::default(),
            r_addr: Default::default(),
            pos: Default::default(),
            lev0: Default::default(),
            lev1: Default::default(),
            lev2: Default::default(),
            lev3: Default::default(),
            lev4: Default::default(),
            lev5: Default::default(),
            rising: Default::default(),
            p_addr: Default::default(),
            p_pos: Default::default(),
            pos_mem: Default::default(),
            pos_copy: Default::default(),
            lev_mem: Default::default(),
            wi_enable: Default::default(),
            wi_addr: Default::default(),
            wi_pos: Default::default(),
            wi_falling: Default::default(),
            wi_lev: Default::default(),
            wb_enable: Default::default(),
            wb_addr: Default::default(),
            wb_pos: Default::default(),
            wb_ends: Default::default(),
            wb_lev: Default::default(),
            wc_enable: Default::default(),
            wc_addr: Default::default(),
            wc_pos: Default::default(),
            wc_lev: Default::default(),
            wq_enable: Default::default(),
            wq_addr: Default::default(),
            wq_pos: Default::default(),
            wq_lev: Default::default(),
            ends: Default::default(),
            lev_off: Default::default(),
            level_offset: Constant::new(LEVEL_OFFSET.into()),
            amp_msb: Constant::new(((AMP_BITS - 1) as u64).into()),
            rise_bit: Constant::new((POS_BITS as u64).into()),
            bit0: Constant::new(0u64.into()),
            one: Constant::new(1u64.into()),
        }
    }
}

impl Logic for RecordMemory {
    #[hdl_gen]
    fn update(&mut self) {
        self.pos_mem.clock.next = self.clock.val();
        self.pos_copy.clock.next = self.clock.val();
        for i in 0..LEVELS {
            self.lev_mem[i].clock.next = self.clock.val();
            self.wi_lev[i].clock.next = self.clock.val();
            self.wi_lev[i].reset.next = self.reset.val();
            self.wb_lev[i].clock.next = self.clock.val();
            self.wb_lev[i].reset.next = self.reset.val();
            self.wc_lev[i].clock.next = self.clock.val();
            self.wc_lev[i].reset.next = self.reset.val();
            self.wq_lev[i].clock.next = self.clock.val();
            self.wq_lev[i].reset.next = self.reset.val();
        }
        dff_setup!(self, clock, wi_enable, wi_addr, wi_pos, wi_falling, wb_enable, wb_addr, wb_pos, wb_ends, wc_enable, wc_addr, wc_pos, wq_enable, wq_addr, wq_pos);
        self.wi_enable.reset.next = self.reset.val();
        self.wi_addr.reset.next = self.reset.val();
        self.wi_pos.reset.next = self.reset.val();
        self.wi_falling.reset.next = self.reset.val();
        self.wb_enable.reset.next = self.reset.val();
        self.wb_addr.reset.next = self.reset.val();
        self.wb_pos.reset.next = self.reset.val();
        self.wb_ends.reset.next = self.reset.val();
        self.wc_enable.reset.next = self.reset.val();
        self.wc_addr.reset.next = self.reset.val();
        self.wc_pos.reset.next = self.reset.val();
        self.wq_enable.reset.next = self.reset.val();
        self.wq_addr.reset.next = self.reset.val();
        self.wq_pos.reset.next = self.reset.val();

        self.wi_enable.d.next = self.w_enable.val();
        self.wi_addr.d.next = self.w_addr.val();
        self.wi_pos.d.next = self.w_pos.val();
        self.wi_falling.d.next = self.w_amp.val().get_bit(self.amp_msb.val().index());
        self.wi_lev[0].d.next = self.w_left0.val();
        self.wi_lev[1].d.next = self.w_left1.val();
        self.wi_lev[2].d.next = self.w_left2.val();
        self.wi_lev[3].d.next = self.w_right0.val();
        self.wi_lev[4].d.next = self.w_right1.val();
        self.wi_lev[5].d.next = self.w_right2.val();

        // Second stage: the end-level sum `e` (0 in the paper's rule),
        // registered with the record.
        self.ends.next = 0.into();
        if self.relative.val() {
            self.ends.next = bit_cast::<LEVEL_BITS, PIXEL_BITS>(self.wi_lev[0].q.val())
                + bit_cast::<LEVEL_BITS, PIXEL_BITS>(self.wi_lev[3].q.val());
        }
        self.wb_ends.d.next = self.ends.val();
        self.wb_pos.d.next = bit_cast::<{ POS_BITS + 1 }, POS_BITS>(self.wi_pos.q.val())
            .replace_bit(self.rise_bit.val().index(), !self.wi_falling.q.val());
        for i in 0..LEVELS {
            self.wb_lev[i].d.next = self.wi_lev[i].q.val();
        }
        self.wb_enable.d.next = self.wi_enable.q.val();
        self.wb_addr.d.next = self.wi_addr.q.val();
        // Third stage: each level `(2·I + LEVEL_OFFSET) - e`, in the RAMs'
        // format. `2·I < LEVEL_OFFSET`, a power of two: the sum is `I` one
        // bit up with the offset's bit set, no adder.
        // (The shifts unrolled: rust-hdl's hdl_gen cannot shift inside a
        // loop over its index.)
        self.lev_off[0].next = (bit_cast::<LEVEL_BITS, PIXEL_BITS>(self.wb_lev[0].q.val()) << self.one.val())
            | self.level_offset.val();
        self.lev_off[1].next = (bit_cast::<LEVEL_BITS, PIXEL_BITS>(self.wb_lev[1].q.val()) << self.one.val())
            | self.level_offset.val();
        self.lev_off[2].next = (bit_cast::<LEVEL_BITS, PIXEL_BITS>(self.wb_lev[2].q.val()) << self.one.val())
            | self.level_offset.val();
        self.lev_off[3].next = (bit_cast::<LEVEL_BITS, PIXEL_BITS>(self.wb_lev[3].q.val()) << self.one.val())
            | self.level_offset.val();
        self.lev_off[4].next = (bit_cast::<LEVEL_BITS, PIXEL_BITS>(self.wb_lev[4].q.val()) << self.one.val())
            | self.level_offset.val();
        self.lev_off[5].next = (bit_cast::<LEVEL_BITS, PIXEL_BITS>(self.wb_lev[5].q.val()) << self.one.val())
            | self.level_offset.val();
        for i in 0..LEVELS {
            self.wc_lev[i].d.next = self.lev_off[i].val() - self.wb_ends.q.val();
        }
        self.wc_pos.d.next = self.wb_pos.q.val();
        self.wc_enable.d.next = self.wb_enable.q.val();
        self.wc_addr.d.next = self.wb_addr.q.val();
        // Fourth stage: the same, beside the RAMs.
        self.wq_pos.d.next = self.wc_pos.q.val();
        self.wq_enable.d.next = self.wc_enable.q.val();
        self.wq_addr.d.next = self.wc_addr.q.val();
        self.pos_mem.write_data.next = self.wq_pos.q.val();
        self.pos_mem.write_address.next = bit_cast::<DIAG_BITS, COPY_ADDR_BITS>(self.wq_addr.q.val());
        self.pos_mem.write_enable.next = self.wq_enable.q.val();
        self.pos_mem.read_address.next = self.r_addr.val();
        for i in 0..LEVELS {
            self.wq_lev[i].d.next = self.wc_lev[i].q.val();
            self.lev_mem[i].write_data.next = self.wq_lev[i].q.val();
            self.lev_mem[i].write_address.next = bit_cast::<DIAG_BITS, COPY_ADDR_BITS>(self.wq_addr.q.val());
            self.lev_mem[i].write_enable.next = self.wq_enable.q.val();
            self.lev_mem[i].read_address.next = self.r_addr.val();
        }
        self.pos_copy.write_data.next = self.wq_pos.q.val().get_bits::<POS_BITS>(self.bit0.val().index());
        self.pos_copy.write_address.next = self.wq_addr.q.val();
        self.pos_copy.write_enable.next = self.wq_enable.q.val();
        self.pos_copy.read_address.next = self.p_addr.val();
        self.p_pos.next = self.pos_copy.read_data.val();
        self.pos.next = self.pos_mem.read_data.val().get_bits::<POS_BITS>(self.bit0.val().index());
        self.lev0.next = self.lev_mem[0].read_data.val();
        self.lev1.next = self.lev_mem[1].read_data.val();
        self.lev2.next = self.lev_mem[2].read_data.val();
        self.lev3.next = self.lev_mem[3].read_data.val();
        self.lev4.next = self.lev_mem[4].read_data.val();
        self.lev5.next = self.lev_mem[5].read_data.val();
        self.rising.next = self.pos_mem.read_data.val().get_bit(self.rise_bit.val().index());
    }
}
