// The interpolator's line queue's contract (rtl::post::interpolator),
// spliced into its generated module `top` before `endmodule` and proven by
// SymbiYosys with k-induction (sim::hdl::formal). Its inputs are free: any
// match, marker, width and reset on any clock. The contract reads no data,
// so the block RAMs and the multipliers are sim::hdl::formal::free_primitive
// (any output on any clock), which also frees the pixel engine's end of a
// line. Parameters: PTR (pointer bits), LINES (the queue's places), LAG
// (clocks from a line's marker to its description shown to the engine).
`ifdef FORMAL
    reg f_past = 1'b0;
    always @(posedge clock) f_past <= 1'b1;
    // The queue's writes of the last LAG - 1 clocks, newest in bit 0.
    reg [LAG-2:0] f_recent = 0;
    always @(posedge clock) if (reset) f_recent <= 0; else f_recent <= {f_recent[LAG-3:0], line_write};
    integer f_i;
    reg [PTR-1:0] f_young;
    always @(*) begin
        f_young = 0;
        for (f_i = 0; f_i < LAG - 1; f_i = f_i + 1) f_young = f_young + f_recent[f_i];
    end
    // Descriptions written and not yet done; those written LAG clocks ago
    // or earlier and not done (the ones the engine may be shown).
    wire [PTR-1:0] f_held = q_wp$q - q_rp$q;
    wire [PTR-1:0] f_old = f_held - f_young;
    // The write pointer's delay line to the engine (q_wp1..5), stage by
    // stage (differences modulo the pointers, as they wrap).
    wire [PTR-1:0] f_step1 = q_wp$q - q_wp1$q;
    wire [PTR-1:0] f_step2 = q_wp1$q - q_wp2$q;
    wire [PTR-1:0] f_step3 = q_wp2$q - q_wp3$q;
    wire [PTR-1:0] f_step4 = q_wp3$q - q_wp4$q;
    wire [PTR-1:0] f_step5 = q_wp4$q - q_wp5$q;
    wire [PTR-1:0] f_rp_next = q_rp$q + 1'b1;
    always @(*) begin
        // No overflow: at most LINES descriptions held, none written over
        // one the engine has not done.
        assert(f_held <= LINES);
        if (line_write) assert(f_held < LINES);
        // No underflow, and no line shown early: the engine works on (and
        // ends) a line only while one written LAG clocks ago or earlier is
        // not done.
        assert(f_young <= f_held);
        if (line_ready$q) assert(f_old != 0);
        if (line_done) assert(line_ready$q);
        // The delay line holds the writes of the last clocks, one a stage.
        assert(f_step1 == f_recent[0]);
        assert(f_step2 == f_recent[1]);
        assert(f_step3 == f_recent[2]);
        assert(f_step4 == f_recent[3]);
        assert(f_step5 == f_recent[4]);
        // The count: descriptions written minus lines done; the flag is the
        // count's; the successor's pointer is the pointer's successor.
        assert(q_used$q == f_held);
        assert(q_full$q == (q_used$q >= LINES));
        assert(q_rp1$q == f_rp_next);
        // Admission: a line being received that was admitted has its place
        // (nothing but its own marker fills the queue), and a line that
        // starts while the queue and the segment memory have room is
        // admitted.
        if (in_line$q && !dropping$q) assert(q_used$q < LINES);
        if (first_event && q_used$q < LINES && !seg_full$q) assert(fits);
    end
    // A reset empties the queue: pointers, counts and the engine.
    always @(posedge clock) if (f_past && $past(reset)) begin
        assert(q_wp$q == 0 && q_rp$q == 0 && q_used$q == 0 && !line_ready$q && !q_full$q);
    end
`endif
