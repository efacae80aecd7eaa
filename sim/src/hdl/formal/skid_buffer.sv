// The camera register slice's contract (rtl::stream::skid_buffer), spliced
// into its generated module `top` before `endmodule` and proven by
// SymbiYosys with k-induction (sim::hdl::formal). The camera side is left
// free: any s_tvalid, s_tdata, s_tuser, s_tlast, m_tready and reset on any
// clock. A reset empties the slice and the reference queue alike.
//
// A reference queue of the beats accepted and not yet taken (two at most:
// the output register and the skid register) states what the slice must
// hold; the asserts tie the slice's registers to it.
`ifdef FORMAL
    reg f_past = 1'b0;
    always @(posedge clock) f_past <= 1'b1;

    wire f_push = s_tvalid & s_tready;
    wire f_pop = m_tvalid & m_tready;
    wire [WIDTH+1:0] f_beat = {s_tdata, s_tuser, s_tlast};
    reg [1:0] f_count = 2'd0;
    reg [WIDTH+1:0] f_head = 0;
    reg [WIDTH+1:0] f_next = 0;
    always @(posedge clock) begin
        if (reset) f_count <= 2'd0;
        else case ({f_push, f_pop})
            2'b10: begin
                if (f_count == 2'd0) f_head <= f_beat; else f_next <= f_beat;
                f_count <= f_count + 2'd1;
            end
            2'b01: begin
                f_head <= f_next;
                f_count <= f_count - 2'd1;
            end
            2'b11: begin
                if (f_count == 2'd1) f_head <= f_beat; else begin f_head <= f_next; f_next <= f_beat; end
            end
            default: ;
        endcase
    end

    always @(*) begin
        // Two beats at most, and they are the slice's: the output register
        // holds the oldest, the skid register the next.
        assert(f_count <= 2'd2);
        assert(f_count == {1'b0, o_valid$q} + {1'b0, k_valid$q});
        assert(!k_valid$q || o_valid$q);
        if (o_valid$q) assert({m_tdata, m_tuser, m_tlast} == f_head);
        if (k_valid$q) assert({k_data$q, k_user$q, k_last$q} == f_next);
        // s_tready is high exactly while the skid register is empty.
        assert(s_tready == !k_valid$q);
    end

    always @(posedge clock) if (f_past) begin
        // AXI4-Stream towards the detector: a beat offered and not taken
        // stays, unchanged, unless a reset came.
        if ($past(m_tvalid && !m_tready && !reset)) begin
            assert(m_tvalid);
            assert({m_tdata, m_tuser, m_tlast} == $past({m_tdata, m_tuser, m_tlast}));
        end
        // Never held while the detector is ready.
        if ($past(m_tready)) assert(s_tready);
    end
`endif
