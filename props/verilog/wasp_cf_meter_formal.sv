// wasp_cf_meter_formal.sv -- formal wrapper of wasp_cf_meter, wasp-m's CF
// meter, alone (yosys read_verilog -formal; yosys-smtbmc + z3). Run by
// prove.sh (rows M and MCOVER); see README.md.
//
// Every input is free in every cycle (rst is high in the first): the meter
// takes any launch flag, any 2-bit miss count and any load enable. The
// specification (rtl/src/cf_meter.rs, props property (l)) is computed here
// in 10-bit arithmetic, in which nothing can wrap:
//   sum  = acc + misses               (<= 130)
//   acc' = min(sum, 127)              every loading cycle
//   a launch with launches == 15 (the 16th of the window):
//          cf_q' = acc' >> 2, launches' = 0, acc' = 0
//   any other launch: launches' = launches + 1; no launch: launches, cf_q hold
//   not loading (a fault in the scheduler): every register holds
//   reset: launches = 0, acc = 0, cf_q = 10 (2.5)
//
// Properties (ASSERT_M), each assertion labelled:
//   m_next       the next state equals the specification (and m_hold,
//                m_reset: holding and reset)
//   m_cf_range   the CF the specification loads is at most 31: it fits the
//                5-bit register, the datapath's CF input, with nothing cut
//   m_acc_sat    the accumulator saturates: a sum above 127 leaves 127
//   m_acc_mono   it never wraps: within a window it never decreases
// The checks relate a cycle to the one before, so k-induction proves them
// from EVERY state of the 16 register bits, reachable or not.
// Covers (COVER): a window loads a CF other than the one held, the
// accumulator saturates, a saturated window loads CF 31 (7.75).

`default_nettype none

module wasp_cf_meter_formal (
    input wire       clk,
    input wire       rst,
    input wire       load,
    input wire       launched,
    input wire [1:0] misses
);
    wire [3:0] launches;
    wire [6:0] acc;
    wire [4:0] cf_q;

    wasp_cf_meter dut (
        .clk(clk), .rst(rst), .load(load), .launched(launched), .misses(misses),
        .launches(launches), .acc(acc), .cf_q(cf_q)
    );

    reg f_init = 1'b1;
    always @(posedge clk) f_init <= 1'b0;
    always @(*) if (f_init) assume(rst);

    // ---- the specification of the next state, 10 bits wide ----
    wire [9:0] l   = {6'd0, launches};
    wire [9:0] a   = {3'd0, acc};
    wire [9:0] q   = {5'd0, cf_q};
    wire [9:0] sum = a + {8'd0, misses};
    wire [9:0] sat = (sum > 10'd127) ? 10'd127 : sum;
    wire       window_end = launched && (l + 10'd1 == 10'd16);
    wire [9:0] l_next = window_end ? 10'd0 : (launched ? l + 10'd1 : l);
    wire [9:0] a_next = window_end ? 10'd0 : sat;
    wire [9:0] q_next = window_end ? (sat >> 2) : q;

    // ---- the previous cycle ----
    reg        p_valid = 1'b0;
    reg        p_rst, p_load, p_end;
    reg [9:0]  p_l, p_a, p_q, p_l_next, p_a_next, p_q_next, p_sum;
    always @(posedge clk) begin
        p_valid  <= 1'b1;
        p_rst    <= rst;
        p_load   <= load;
        p_end    <= window_end;
        p_l      <= l;
        p_a      <= a;
        p_q      <= q;
        p_l_next <= l_next;
        p_a_next <= a_next;
        p_q_next <= q_next;
        p_sum    <= sum;
    end

`ifdef ASSERT_M
    always @(*) begin
        m_cf_range: assert(q_next <= 10'd31);
        if (p_valid && p_rst)
            m_reset: assert(l == 10'd0 && a == 10'd0 && q == 10'd10);
        if (p_valid && !p_rst && !p_load)
            m_hold: assert(l == p_l && a == p_a && q == p_q);
        if (p_valid && !p_rst && p_load) begin
            m_next: assert(l == p_l_next && a == p_a_next && q == p_q_next);
            if (!p_end && p_sum > 10'd127) m_acc_sat: assert(a == 10'd127);
            if (!p_end) m_acc_mono: assert(a >= p_a);
        end
    end
`endif

`ifdef COVER
    always @(*) if (p_valid && !p_rst && p_load) begin
        // a window end loads a CF other than the one held
        c_window: cover(p_end && q != p_q);
        // the accumulator saturates: a sum above 127 is held at 127
        c_saturate: cover(!p_end && p_sum > 10'd127 && a == 10'd127);
        // a saturated window loads the largest CF, 31 (7.75)
        c_cf_max: cover(p_end && q == 10'd31);
    end
`endif
endmodule

`default_nettype wire
