// wasp_sched_formal.sv -- formal wrapper of wasp_sched (yosys read_verilog
// -formal; yosys-smtbmc + z3). Run by prove.sh; see README.md.
//
// The block is read with WASP_CFG_PORTS defined, so its configuration comes
// from ports, driven here by $anyconst: every proof covers every
// configuration at once -- policy 0..4 (baseline, fullpriority, freemshr-N,
// wasp, wasp-m), MSHR capacity 0..31, CF_Q 0..31 (CF 0..7.75), threshold 0..31,
// N 0..31, queue capacity 0..2**OCC_W-1 (0..127), launch rule 0 (hold) and
// 1 (launch). MESH_BITS (Mesh4 by default) and the widths are parameters.
//
// The per-cycle inputs are free. Unless FAULT_MODE is defined they are
// assumed LEGAL with respect to an auxiliary reference model kept here in
// AW-bit signed arithmetic, independent of the block's registers:
//   aux_inflight   MSHR entries allocated and not yet replied
//   aux_nb/aux_bl  priority warps in the core, non-blocked / blocked
//   aux_pw/aux_rw  warps waiting in the priority / regular FIFO
//   aux_ml/aux_ma/aux_mq  wasp-m's CF meter as specified: priority launches
//                  in the window, misses accumulated (min(acc + misses, 127),
//                  misses clamped to 3), the CF loaded every 16th launch
//                  (acc >> 2; 10 after reset)
// Legal (as wasp-props' MshrModel / PriorityModel and FreeMshrReg::legal):
//   replies <= inflight; allocs <= (capacity - inflight) + replies;
//   unblocked <= blocked; blocked + finished <= nonblocked +
//   (priority launch this cycle) + unblocked; a priority launch only while
//   fewer than 127 priority warps are in the core. Event counts are 8 bits
//   (the Rust u8); rst may be raised at any cycle, and is in the first.
//
// "Exact" below = AW-bit (13) signed arithmetic on values that cannot
// overflow it (-3937 <= 4*free - q*nb <= 124; event sums -510..+766), with
// q*nb as a 5 x 7-bit multiplication into 12 bits (<= 3937 < 4096). q is
// CF_Q, or for wasp-m the CF of the reference meter (aux_mq). The
// widths are sized on purpose: a 32-bit multiplier compared against the
// shift-add is a needlessly hard problem for the SAT solver.
//
// Properties, each enabled by a define so that prove.sh proves them group
// by group, each assertion labelled (the label names the property):
//   P1  a priority selection or launch only when
//       4*(capacity - inflight) - q*nb > 4*T on the reference model (wasp,
//       wasp-m), or, under the launch rule `launch`, when no regular warp waits
//   P2  product == floor(q*nb/4); real_free == free - floor(q*nb/4) as a
//       signed value (the 11-bit subtract never wraps);
//       priority_over_regular == (4*free - q*nb > 4*T), q the datapath's CF
//       input (cf_q: CF_Q, or wasp-m's meter register); for EVERY register
//       value (asserted in every state, reachable or not)
//   P3  free_mshrs == capacity - inflight and inflight <= capacity (so
//       free_mshrs never exceeds the capacity and never wraps)
//   P4  nonblocked == aux_nb, and aux_nb + aux_bl <= 127 (never wraps)
//   P5  prio_occ == aux_pw, reg_occ == aux_rw, aux_pw + aux_rw <= queue
//       capacity; is_priority == the Mesh-k rule in arithmetic (x mod k == 0
//       and y mod k == 0; never for the baseline); push accepted exactly
//       when push_valid and the queue is not full
//   P6  no fault under legal inputs
//   P7  select and launch equal the reference policy on the reference
//       model (a FIFO is non-empty if it holds a warp or accepts one now;
//       launch = select when launch_enable)
//   PM  wasp-m's CF meter equals the reference meter (launch count and
//       accumulator for every policy, the CF under wasp-m), which stays in
//       range: launches 0..15, accumulator 0..127 (saturating, never
//       wrapping), CF 0..31 (the datapath's 5-bit CF input)
//   P9  the launch rule, every policy: under `hold` a priority warp never
//       launches with the gate closed (on the reference model); under
//       `launch` the core never idles while a warp waits and launch_enable
//       is high; a core that idles with a warp waiting and launch_enable high
//       is exactly a `hold` with a lone priority warp and the gate closed
//   P8  (FAULT_MODE: no legality assumptions) fault == the exact next value
//       of either register leaves its range; on a fault both registers hold,
//       otherwise both load the exact values; a reset loads capacity and 0s
//       (and the meter's CF 10); on a fault the CF meter holds too
// Cover statements (COVER): the interesting cases are reachable.

`default_nettype none

module wasp_sched_formal #(
    parameter integer MESH_BITS = 2,
    parameter integer OCC_W     = 7,
    // width of the exact arithmetic (see above)
    parameter integer AW        = 13
) (
    input wire       clk,
    input wire       rst,
    input wire       push_valid,
    input wire [4:0] qx,
    input wire [4:0] qy,
    input wire       launch_enable,
    input wire [7:0] mshr_allocs,
    input wire [7:0] mshr_replies,
    input wire [7:0] prio_blocked,
    input wire [7:0] prio_unblocked,
    input wire [7:0] prio_finished,
    input wire [7:0] prio_misses
);
    // ---- any configuration, constant over the run ----
    wire [2:0]       cfg_policy     = $anyconst;
    wire [4:0]       cfg_capacity   = $anyconst;
    wire [4:0]       cfg_cf_q       = $anyconst;
    wire [4:0]       cfg_threshold  = $anyconst;
    wire [4:0]       cfg_freemshr_n = $anyconst;
    wire [OCC_W-1:0] cfg_queue_cap  = $anyconst;
    wire             cfg_launch_rule = $anyconst;   // 0 hold, 1 launch

    wire [4:0]       free_mshrs;
    wire [6:0]       nonblocked;
    wire [OCC_W-1:0] prio_occ, reg_occ;
    wire             is_priority, push_accepted;
    wire [9:0]       product;
    wire [10:0]      real_free;
    wire             priority_over_regular;
    wire [1:0]       select, launch;
    wire             fault;
    wire [3:0]       meter_launches;
    wire [6:0]       meter_acc;
    wire [4:0]       cf_q;

    always @(*) assume(cfg_policy <= 3'd4);

    wasp_sched #(
        // the configuration parameters are unused with WASP_CFG_PORTS
        .MESH_BITS(MESH_BITS), .OCC_W(OCC_W), .CNT_W(8), .QUEUE_CAP(0)
    ) dut (
        .clk(clk), .rst(rst),
        .cfg_policy(cfg_policy),
        .cfg_capacity(cfg_capacity), .cfg_cf_q(cfg_cf_q),
        .cfg_threshold(cfg_threshold), .cfg_freemshr_n(cfg_freemshr_n),
        .cfg_queue_cap(cfg_queue_cap),
        .cfg_launch_rule(cfg_launch_rule),
        .push_valid(push_valid), .qx(qx), .qy(qy),
        .launch_enable(launch_enable),
        .mshr_allocs(mshr_allocs), .mshr_replies(mshr_replies),
        .prio_blocked(prio_blocked), .prio_unblocked(prio_unblocked),
        .prio_finished(prio_finished), .prio_misses(prio_misses),
        .free_mshrs(free_mshrs), .nonblocked(nonblocked),
        .prio_occ(prio_occ), .reg_occ(reg_occ),
        .is_priority(is_priority), .push_accepted(push_accepted),
        .product(product), .real_free(real_free),
        .priority_over_regular(priority_over_regular),
        .select(select), .launch(launch), .fault(fault),
        .meter_launches(meter_launches), .meter_acc(meter_acc), .cf_q(cf_q)
    );

    // ---- the first cycle is a reset; f_init is high only then ----
    reg f_init = 1'b1;
    always @(posedge clk) f_init <= 1'b0;
    always @(*) if (f_init) assume(rst);

    // ---- AW-bit signed views (zero-extended) ----
    wire signed [AW-1:0] cap  = {{(AW-5){1'b0}}, cfg_capacity};
    wire signed [AW-1:0] q    = {{(AW-5){1'b0}}, cfg_cf_q};
    wire signed [AW-1:0] thr  = {{(AW-5){1'b0}}, cfg_threshold};
    wire signed [AW-1:0] nmin = {{(AW-5){1'b0}}, cfg_freemshr_n};
    wire signed [AW-1:0] qcap = {{(AW-OCC_W){1'b0}}, cfg_queue_cap};
    wire signed [AW-1:0] a    = {{(AW-8){1'b0}}, mshr_allocs};
    wire signed [AW-1:0] r    = {{(AW-8){1'b0}}, mshr_replies};
    wire signed [AW-1:0] b    = {{(AW-8){1'b0}}, prio_blocked};
    wire signed [AW-1:0] u    = {{(AW-8){1'b0}}, prio_unblocked};
    wire signed [AW-1:0] f    = {{(AW-8){1'b0}}, prio_finished};
    wire signed [AW-1:0] lp   = {{(AW-1){1'b0}}, launch == 2'd2};
    wire signed [AW-1:0] lr   = {{(AW-1){1'b0}}, launch == 2'd1};
    wire signed [AW-1:0] reg_free = {{(AW-5){1'b0}}, free_mshrs};
    wire signed [AW-1:0] reg_nb   = {{(AW-7){1'b0}}, nonblocked};
    localparam signed [AW-1:0] ZERO = 0, MAXNB = 127, FOUR = 4;
    wire wasp_gate = cfg_policy == 3'd3 || cfg_policy == 3'd4;   // wasp, wasp-m

    // ---- the auxiliary reference model ----
    reg signed [AW-1:0] aux_inflight, aux_nb, aux_bl, aux_pw, aux_rw;
    reg signed [AW-1:0] aux_ml, aux_ma, aux_mq;   // the reference CF meter

    localparam [4:0] K = 5'd1 << MESH_BITS;
    // Mesh-k in arithmetic: x mod k == 0 and y mod k == 0
    wire ref_priority = (cfg_policy != 3'd0) && (qx % K == 5'd0) && (qy % K == 5'd0);
    wire ref_accept   = push_valid && (aux_pw + aux_rw < qcap);
    wire ref_pw = (aux_pw != 0) || (ref_accept && ref_priority);
    wire ref_rw = (aux_rw != 0) || (ref_accept && !ref_priority);
    wire signed [AW-1:0] aux_free = cap - aux_inflight;
    wire               aux_nb_in_range = aux_nb >= ZERO && aux_nb <= MAXNB;
    // the reference CF: the wired one, or wasp-m's reference meter (in range
    // by PM)
    wire         [4:0] q_ref  = (cfg_policy == 3'd4) ? aux_mq[4:0] : cfg_cf_q;
    wire        [11:0] qn_aux = q_ref * aux_nb[6:0];           // exact when in range
    wire signed [AW-1:0] lhs_aux = (aux_free <<< 2) - $signed({{(AW-12){1'b0}}, qn_aux});
    wire signed [AW-1:0] thr4    = thr <<< 2;
    // the exact WaSP condition 4*free - q*nb > 4*T on the reference model
    wire exact_wasp = aux_nb_in_range && (lhs_aux > thr4);
    wire ref_allowed = (cfg_policy == 3'd1) ? 1'b1 :
                       (cfg_policy == 3'd2) ? (aux_free >= nmin) :
                       wasp_gate ? exact_wasp : 1'b0;
    wire [1:0] ref_select = (ref_pw && ref_allowed)    ? 2'd2 :
                            ref_rw                     ? 2'd1 :
                            (ref_pw && cfg_launch_rule) ? 2'd2 : 2'd0;
    wire [1:0] ref_launch = launch_enable ? ref_select : 2'd0;

    // the reference meter's next values (AW bits: nothing wraps)
    wire signed [AW-1:0] m_in  = (prio_misses > 8'd3) ? 3 : {{(AW-8){1'b0}}, prio_misses};
    wire signed [AW-1:0] m_sum = aux_ma + m_in;
    wire signed [AW-1:0] m_sat = (m_sum > MAXNB) ? MAXNB : m_sum;
    wire                 m_end = lp != ZERO && aux_ml == 15;

    always @(posedge clk) begin
        if (rst) begin
            aux_inflight <= ZERO;
            aux_nb       <= ZERO;
            aux_bl       <= ZERO;
            aux_pw       <= ZERO;
            aux_rw       <= ZERO;
            aux_ml       <= ZERO;
            aux_ma       <= ZERO;
            aux_mq       <= 10;
        end else begin
            aux_inflight <= aux_inflight + a - r;
            aux_nb       <= aux_nb + lp + u - b - f;
            aux_bl       <= aux_bl + b - u;
            aux_pw       <= aux_pw + (ref_accept && ref_priority) - lp;
            aux_rw       <= aux_rw + (ref_accept && !ref_priority) - lr;
            aux_ml       <= m_end ? ZERO : aux_ml + lp;
            aux_ma       <= m_end ? ZERO : m_sat;
            aux_mq       <= m_end ? (m_sat >>> 2) : aux_mq;
        end
    end

    // ---- legal inputs ----
`ifndef FAULT_MODE
    always @(*) begin
        if (!rst) begin
            assume(r <= aux_inflight);
            assume(a <= aux_free + r);
            assume(u <= aux_bl);
            assume(b + f <= aux_nb + lp + u);
            if (launch == 2'd2) assume(aux_nb + aux_bl < MAXNB);
        end
    end
`endif

    // ---- P1: a priority launch only under the exact condition ----
`ifdef ASSERT_P1
    // under `launch`, a priority warp below the threshold only when no
    // regular warp waits (the block's own regular FIFO: P1 assumes only P34)
    wire dut_rw = (reg_occ != {OCC_W{1'b0}}) || (push_accepted && !is_priority);
    wire p1_ok  = exact_wasp || (cfg_launch_rule && !dut_rw);
    always @(*) if (!rst && wasp_gate) begin
        if (select == 2'd2) p1_select: assert(p1_ok);
        if (launch == 2'd2) p1_launch: assert(p1_ok);
        if (!cfg_launch_rule && launch == 2'd2) p1_hold: assert(exact_wasp);
    end
`endif

    // ---- P2: the datapath is the exact comparison, for every value ----
`ifdef ASSERT_P2
    wire        [11:0] qn_reg = cf_q * nonblocked;            // exact: <= 3937
    wire signed [AW-1:0] exact_product = {{(AW-10){1'b0}}, qn_reg[11:2]}; // floor(q*nb/4)
    wire signed [AW-1:0] rf_ext = {{(AW-11){real_free[10]}}, real_free};
    wire signed [AW-1:0] lhs_reg = (reg_free <<< 2) - $signed({{(AW-12){1'b0}}, qn_reg});
    always @(*) begin
        p2_product: assert({{(AW-10){1'b0}}, product} == exact_product);
        p2_real_free: assert(rf_ext == reg_free - exact_product);
        p2_compare: assert(priority_over_regular == (lhs_reg > thr4));
    end
`endif

    // P3, P4 (one inductive group: each needs the other, since a fault of
    // either register holds both) and P5 are the strengthening invariants.
    // ASSERT_* proves them; ASSUME_* assumes them, which is sound once the
    // ASSERT_* run of the same group has proved them (prove.sh runs both):
    // they then hold in every reachable state, so assuming them removes no
    // reachable behaviour. No group assumes anything it is used to prove.
`ifdef ASSERT_P34
  `define P34_CHECK assert
`elsif ASSUME_P34
  `define P34_CHECK assume
`endif
`ifdef ASSERT_P5
  `define P5_CHECK assert
`elsif ASSUME_P5
  `define P5_CHECK assume
`endif
`ifdef ASSERT_PM
  `define PM_CHECK assert
`elsif ASSUME_PM
  `define PM_CHECK assume
`endif

`ifdef P34_CHECK
    always @(*) if (!f_init) begin
        // ---- P3: free_mshrs == capacity - outstanding entries ----
        p3_model: `P34_CHECK(aux_inflight >= ZERO && aux_inflight <= cap);
        p3_equal: `P34_CHECK(reg_free == cap - aux_inflight);
        p3_cap:   `P34_CHECK(reg_free <= cap);
        // ---- P4: nonblocked == the model's non-blocked priority warps ----
        // (each term bounded first, so that the sum cannot wrap)
        p4_model: `P34_CHECK(aux_nb >= ZERO && aux_bl >= ZERO && aux_nb <= MAXNB &&
                             aux_bl <= MAXNB && aux_nb + aux_bl <= MAXNB);
        p4_equal: `P34_CHECK(reg_nb == aux_nb);
    end
`endif

    // ---- P5: queue occupancy, capacity and push refusal ----
`ifdef P5_CHECK
    always @(*) begin
        if (!f_init) begin
            p5_model:    `P5_CHECK(aux_pw >= ZERO && aux_rw >= ZERO && aux_pw <= qcap &&
                                   aux_rw <= qcap && aux_pw + aux_rw <= qcap);
            p5_prio_occ: `P5_CHECK({{(AW-OCC_W){1'b0}}, prio_occ} == aux_pw);
            p5_reg_occ:  `P5_CHECK({{(AW-OCC_W){1'b0}}, reg_occ} == aux_rw);
        end
        if (!rst) begin
            p5_class:    `P5_CHECK(is_priority == ref_priority);
            p5_push:     `P5_CHECK(push_accepted == ref_accept);
        end
    end
`endif

    // ---- PM: wasp-m's CF meter equals its specification, in range ----
    // (the meter runs under every policy; its CF is read, and visible at
    // cf_q, only under wasp-m)
`ifdef PM_CHECK
    always @(*) if (!f_init) begin
        pm_model: `PM_CHECK(aux_ml >= ZERO && aux_ml <= 15 && aux_ma >= ZERO && aux_ma <= MAXNB &&
                            aux_mq >= ZERO && aux_mq <= 31);
        pm_launches: `PM_CHECK({{(AW-4){1'b0}}, meter_launches} == aux_ml);
        pm_acc:      `PM_CHECK({{(AW-7){1'b0}}, meter_acc} == aux_ma);
        if (cfg_policy == 3'd4) pm_cf: `PM_CHECK({{(AW-5){1'b0}}, cf_q} == aux_mq);
        else pm_cf_wired: `PM_CHECK(cf_q == cfg_cf_q);
    end
`endif

    // ---- P6: no fault under legal inputs ----
`ifdef ASSERT_P6
    always @(*) if (!rst) p6_no_fault: assert(!fault);
`endif

    // ---- P7: the launch equals the reference policy ----
`ifdef ASSERT_P7
    always @(*) if (!rst) begin
        p7_select: assert(select == ref_select);
        p7_launch: assert(launch == ref_launch);
    end
`endif

    // ---- P9: the launch rule ----
`ifdef ASSERT_P9
    wire ref_waiting = ref_pw || ref_rw;
    always @(*) if (!rst) begin
        // hold: a closed gate never launches a priority warp
        if (!cfg_launch_rule && launch == 2'd2) p9_hold: assert(ref_allowed);
        // launch: never idle while a warp waits
        if (cfg_launch_rule && launch_enable && ref_waiting) p9_work_conserving: assert(launch != 2'd0);
        // idling with a warp waiting is exactly hold's lone priority warp
        if (launch_enable && ref_waiting && launch == 2'd0)
            p9_idle_is_hold: assert(!cfg_launch_rule && ref_pw && !ref_rw && !ref_allowed);
    end
`endif

    // ---- P8: fault semantics, without legality assumptions ----
`ifdef ASSERT_P8
    wire signed [AW-1:0] exact_free_next = reg_free - a + r;
    wire signed [AW-1:0] exact_nb_next   = reg_nb + lp + u - b - f;
    wire exact_fault = exact_free_next < 0 || exact_free_next > cap ||
                       exact_nb_next < 0 || exact_nb_next > MAXNB;
    reg        p_valid = 1'b0;
    reg        p_rst, p_fault;
    reg [AW-1:0] p_free, p_nb, p_free_next, p_nb_next;
    reg [15:0] p_meter;
    always @(posedge clk) begin
        p_valid     <= 1'b1;
        p_rst       <= rst;
        p_fault     <= fault;
        p_free      <= reg_free;
        p_nb        <= reg_nb;
        p_free_next <= exact_free_next;
        p_nb_next   <= exact_nb_next;
        p_meter     <= {meter_launches, meter_acc, cf_q};
    end
    always @(*) begin
        if (!rst) p8_fault: assert(fault == exact_fault);
        if (p_valid && p_rst)
            p8_reset: assert(reg_free == cap && reg_nb == ZERO && prio_occ == 0 && reg_occ == 0 &&
                             meter_launches == 4'd0 && meter_acc == 7'd0 &&
                             cf_q == ((cfg_policy == 3'd4) ? 5'd10 : cfg_cf_q));
        if (p_valid && !p_rst && p_fault)
            p8_hold: assert(reg_free == p_free && reg_nb == p_nb &&
                            {meter_launches, meter_acc, cf_q} == p_meter);
        if (p_valid && !p_rst && !p_fault)
            p8_load: assert(reg_free == p_free_next && reg_nb == p_nb_next);
    end
`endif

    // ---- covers: the cases worth seeing are reachable ----
`ifdef COVER
    always @(*) if (!rst && !f_init) begin
        // a priority launch at the boundary 4*T < 4*free - q*nb <= 4*T + 4
        c_boundary: cover(cfg_policy == 3'd3 && launch == 2'd2 && aux_nb > ZERO && q > ZERO &&
                          lhs_aux <= thr4 + FOUR);
        // a waiting priority warp held back, a regular warp launched instead
        c_held_back: cover(launch == 2'd1 && aux_pw != ZERO);
        // a push refused by a full queue holding warps of both classes
        c_full: cover(push_valid && !push_accepted && aux_pw != ZERO && aux_rw != ZERO);
        // every MSHR taken while priority warps run
        c_no_free: cover(free_mshrs == 5'd0 && cap > 2 && nonblocked > 7'd1);
        // real_free negative
        c_negative: cover(real_free[10] && nonblocked > 7'd1);
        // several warps finish, block and unblock in one cycle
        c_events: cover(prio_finished > 8'd1 && prio_blocked > 8'd1 && prio_unblocked > 8'd1);
        // hold: a lone priority warp, gate closed, a free slot, nothing launched (wasp)
        c_hold: cover(cfg_policy == 3'd3 && !cfg_launch_rule && launch_enable && launch == 2'd0 &&
                      aux_pw != ZERO && aux_rw == ZERO);
        // launch: a priority warp launched with the WaSP gate closed
        c_launch_closed: cover(cfg_policy == 3'd3 && cfg_launch_rule && launch == 2'd2 && !exact_wasp);
        // wasp-m: a priority launch counted by the meter with misses in its
        // window, and a miss count above 3 (clamped)
        c_waspm: cover(cfg_policy == 3'd4 && launch == 2'd2 && meter_launches > 4'd1 &&
                       meter_acc > 7'd3 && prio_misses > 8'd3);
    end
`endif
endmodule

`default_nettype wire
