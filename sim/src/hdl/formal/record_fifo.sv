// The record queue's contract (rtl::stream::record_fifo), spliced into its
// generated module `top` before `endmodule` and proven by SymbiYosys with
// k-induction (sim::hdl::formal). Its inputs are free: any w_valid,
// w_marker, lanes, r_ready and reset on any clock; a reset empties the
// queue and the reference counts alike. The contract reads no data, so
// the block RAMs are sim::hdl::formal::free_dp16kd (any read value).
// Parameters: PTR (pointer bits), DEPTH (beats), AHEAD (the ring's places).
`ifdef FORMAL
    reg f_past = 1'b0;
    always @(posedge clock) f_past <= 1'b1;
    // Beats that left (r_valid && r_ready), counted modulo the pointers.
    reg [PTR-1:0] f_pops = 0;
    always @(posedge clock) if (reset) f_pops <= 0; else if (r_valid & r_ready) f_pops <= f_pops + 1'b1;
    // The last beat written was a record (not a marker).
    reg f_record_last = 1'b0;
    always @(posedge clock) if (reset) f_record_last <= 1'b0; else if (write) f_record_last <= !w_marker;
    wire [PTR-1:0] f_in_ram = wp$q - rp$q;
    wire [PTR-1:0] f_held = wp$q - f_pops;
    wire [3:0] f_ahead = {1'b0, fill$q} + {3'b0, rd1$q} + {3'b0, rd2$q};
    always @(*) begin
        // No overflow: at most DEPTH beats held, none written over one unread.
        assert(f_held <= DEPTH);
        assert(f_in_ram <= DEPTH);
        if (write) assert(f_in_ram < DEPTH);
        // No underflow: a beat leaves only from the ring, read only once written.
        assert(r_valid == (fill$q != 0));
        if (issue) assert(rp$q != wp$q);
        // The count: writes minus beats that left (a beat that left counted a clock later).
        assert(used$q == f_held + {{(PTR-1){1'b0}}, popped$q});
        assert(popped$q == 1'b0 || used$q != 0);
        // What is between the RAM and the output: the reads on their way and the ring.
        assert(rp$q - f_pops == {{(PTR-4){1'b0}}, f_ahead});
        assert(f_ahead <= AHEAD);
        assert(wi$q - ri$q == fill$q);
        // The flags are the count's.
        assert(full_rec$q == (used$q >= DEPTH - 1));
        assert(full_mark$q == (used$q >= DEPTH));
        // A line's marker is never cut: after a record was written, a place
        // stays free until a marker takes it.
        if (f_record_last) assert(used$q <= DEPTH - 1);
        if (w_valid && w_marker && f_record_last) assert(write);
        // A record is written only while two places are free.
        if (write && !w_marker) assert(used$q <= DEPTH - 2);
    end
`endif
