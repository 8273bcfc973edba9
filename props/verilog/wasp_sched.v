// wasp_sched.v -- the Verilog twin of wasp-rtl's LaunchScheduler
// (rtl/src/scheduler.rs with the Mesh-k subset and the policies of
// rtl/src/policy), synthesizable Verilog-2005.
//
// One block per wasp-rtl block, so that `synth` without -flatten reports
// each block's cells separately:
//
//   wasp_mesh_cmp       subset/mesh.rs   Mesh-k comparator on the enqueue path
//   wasp_split_queue    queue.rs         priority/regular occupancy counters
//                                        sharing QUEUE_CAP slots
//   wasp_free_mshr_reg  free_mshr.rs     5-bit free-MSHR register
//   wasp_nonblocked_ctr nonblocked.rs    7-bit non-blocked priority counter
//   wasp_cf_datapath    datapath.rs      x CF shift-add, 11-bit subtract, compare
//   wasp_launch_select  policy/*.rs      baseline / fullpriority / freemshr-N / wasp /
//                                        wasp-m, launch rule hold / launch
//   wasp_cf_meter       cf_meter.rs      wasp-m's CF meter: 4-bit launch window,
//                                        7-bit saturating miss accumulator, 5-bit CF
//   wasp_sched          scheduler.rs     the above, one per core
//
// Configuration. Each constant is a parameter of the block that uses it
// (so synthesis folds it: the shift-add keeps only the partial products of
// the set bits of CF_Q). When the macro WASP_CFG_PORTS is defined, as the
// formal wrapper does, the constants instead come from input ports cfg_*
// (same logic, same source text), so that one proof covers every policy,
// capacity, CF, threshold, N, queue capacity and launch rule at once.
//
// POLICY 4 is wasp-m (beyond the paper): WaSP whose datapath multiplies by
// the CF register of a CF meter (wasp_cf_meter) instead of the constant
// CF_Q. The meter exists only under POLICY 4 (with WASP_CFG_PORTS it is
// always there and the datapath reads it when cfg_policy is 4).
//
// Timing: cycle-exact with wasp-rtl under the call order of one cycle
//     enqueue -> launch -> clock
//   * free_mshrs, nonblocked, prio_occ, reg_occ are register outputs (Q): the
//     values at the start of the cycle, before this cycle's push and pop.
//   * is_priority, push_accepted: the Mesh-k comparator on (qx, qy) (always 0
//     for the baseline) and the capacity check: a push is refused iff
//     prio_occ + reg_occ >= QUEUE_CAP (Q values: the push comes before the
//     pop of the same cycle).
//   * product, real_free, priority_over_regular: the datapath on the Q
//     values of free_mshrs and nonblocked.
//   * select: the policy's choice under the launch rule (LAUNCH_RULE 0 hold:
//     a priority warp waiting with the gate closed and no regular warp
//     waiting launches nothing; 1 launch: it launches); a FIFO counts as
//     non-empty if it held a
//     warp at the start of the cycle or accepted one this cycle (a warp
//     pushed in a cycle can launch in that cycle). launch = select when
//     launch_enable, else 0 (0 none, 1 regular, 2 priority); it pops.
//   * clock edge: occupancies load Q + push - pop; free_mshrs loads
//     free - allocs + replies; nonblocked loads
//     count + (launch == 2) + unblocked - blocked - finished. If either exact
//     value leaves its register's range (free: 0..=capacity, counter:
//     0..=127) `fault` is high in that cycle and BOTH registers hold (wasp-rtl
//     returns RegisterFault and loads neither); the queue still pops/pushes.
//   * the CF meter (wasp-m) loads at the same edge, from this cycle's
//     priority launch (launch == 2) and prio_misses clamped to its 2-bit
//     input (3); on a fault it holds too (wasp-rtl's clock returns the
//     fault before it reaches the meter).
//   * rst (synchronous, active high): free_mshrs <= capacity, the meter's
//     CF <= 10 (2.5), all else 0.

`default_nettype none

// Lint (verilator --lint-only -Wall, run by .ci/run): one file holds every
// module of the twin, one per wasp-rtl block, so that `wasp cost` embeds a
// single file; the module names cannot all match the file name.
/* verilator lint_off DECLFILENAME */
`ifdef WASP_CFG_PORTS
// With the configuration ports the blocks' parameters are not read: the
// ports replace them (same source text, one proof for every configuration).
/* verilator lint_off UNUSEDPARAM */
`endif

// ---------------------------------------------------------------------------
// Mesh-k comparator: a quad is a priority warp iff the low MESH_BITS bits of
// its in-tile quad x and y are zero (Mesh4: two bits each). The baseline
// policy has no priority warps.
module wasp_mesh_cmp #(
    parameter integer MESH_BITS = 2,
    parameter integer POLICY    = 3
) (
`ifdef WASP_CFG_PORTS
    input  wire [2:0] cfg_policy,
`endif
    // The whole in-tile quad coordinate comes in; Mesh-k reads only its low
    // MESH_BITS bits.
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [4:0] qx,
    input  wire [4:0] qy,
    /* verilator lint_on UNUSEDSIGNAL */
    output wire       is_priority
);
`ifndef WASP_CFG_PORTS
    wire [2:0] cfg_policy = POLICY[2:0];
`endif
    wire hit = (qx[MESH_BITS-1:0] == {MESH_BITS{1'b0}}) &&
               (qy[MESH_BITS-1:0] == {MESH_BITS{1'b0}});
    assign is_priority = (cfg_policy != 3'd0) && hit;
endmodule

// ---------------------------------------------------------------------------
// The split input queue's bookkeeping: two occupancy counters drawing on
// QUEUE_CAP shared slots. (The warp storage itself, one RAM with two
// head/tail pointer pairs, is not modelled: the decision depends only on
// which FIFO is non-empty.)
module wasp_split_queue #(
    parameter integer QUEUE_CAP = 64,
    parameter integer OCC_W     = 7
) (
    input  wire             clk,
    input  wire             rst,
`ifdef WASP_CFG_PORTS
    input  wire [OCC_W-1:0] cfg_queue_cap,
`endif
    input  wire             push_valid,
    input  wire             push_priority,
    input  wire             pop_priority,
    input  wire             pop_regular,
    output reg  [OCC_W-1:0] prio_occ,
    output reg  [OCC_W-1:0] reg_occ,
    output wire             push_accepted,
    output wire             prio_waiting,   // after this cycle's push
    output wire             reg_waiting
);
`ifndef WASP_CFG_PORTS
    wire [OCC_W-1:0] cfg_queue_cap = QUEUE_CAP[OCC_W-1:0];
`endif
    wire [OCC_W:0] occ_sum = {1'b0, prio_occ} + {1'b0, reg_occ};
    wire           full    = occ_sum >= {1'b0, cfg_queue_cap};
    assign push_accepted = push_valid && !full;
    wire push_p = push_accepted && push_priority;
    wire push_r = push_accepted && !push_priority;
    // 1-bit events zero-extended to the counters' width
    wire [OCC_W-1:0] inc_p = {{(OCC_W-1){1'b0}}, push_p};
    wire [OCC_W-1:0] inc_r = {{(OCC_W-1){1'b0}}, push_r};
    wire [OCC_W-1:0] dec_p = {{(OCC_W-1){1'b0}}, pop_priority};
    wire [OCC_W-1:0] dec_r = {{(OCC_W-1){1'b0}}, pop_regular};
    assign prio_waiting = (prio_occ != {OCC_W{1'b0}}) || push_p;
    assign reg_waiting  = (reg_occ  != {OCC_W{1'b0}}) || push_r;

    always @(posedge clk) begin
        if (rst) begin
            prio_occ <= {OCC_W{1'b0}};
            reg_occ  <= {OCC_W{1'b0}};
        end else begin
            prio_occ <= prio_occ + inc_p - dec_p;
            reg_occ  <= reg_occ  + inc_r - dec_r;
        end
    end
endmodule

// ---------------------------------------------------------------------------
// The 5-bit free-MSHR register: reset to the capacity, loads
// free - allocs + replies. range_fault: that exact value is outside
// 0..=capacity. It loads only when `load` (no fault in the whole block).
module wasp_free_mshr_reg #(
    parameter integer CAPACITY = 16,
    parameter integer CNT_W    = 8
) (
    input  wire             clk,
    input  wire             rst,
`ifdef WASP_CFG_PORTS
    input  wire [4:0]       cfg_capacity,
`endif
    input  wire [CNT_W-1:0] allocs,
    input  wire [CNT_W-1:0] replies,
    input  wire             load,
    output reg  [4:0]       free_mshrs,
    output wire             range_fault
);
`ifndef WASP_CFG_PORTS
    wire [4:0] cfg_capacity = CAPACITY[4:0];
`endif
    // exact, signed, wide enough never to wrap
    localparam integer EW = ((CNT_W > 5) ? CNT_W : 5) + 2;
    wire signed [EW-1:0] next =
          $signed({{(EW-5){1'b0}}, free_mshrs})
        - $signed({{(EW-CNT_W){1'b0}}, allocs})
        + $signed({{(EW-CNT_W){1'b0}}, replies});
    assign range_fault = (next < 0) ||
                         (next > $signed({{(EW-5){1'b0}}, cfg_capacity}));

    always @(posedge clk) begin
        if (rst)
            free_mshrs <= cfg_capacity;
        else if (load)
            free_mshrs <= next[4:0];
    end
endmodule

// ---------------------------------------------------------------------------
// The 7-bit non-blocked priority-warp counter: loads
// count + launched + unblocked - blocked - finished. range_fault: that exact
// value is outside 0..=127.
module wasp_nonblocked_ctr #(
    parameter integer CNT_W = 8
) (
    input  wire             clk,
    input  wire             rst,
    input  wire             launched,
    input  wire [CNT_W-1:0] blocked,
    input  wire [CNT_W-1:0] unblocked,
    input  wire [CNT_W-1:0] finished,
    input  wire             load,
    output reg  [6:0]       nonblocked,
    output wire             range_fault
);
    localparam integer EW = ((CNT_W > 7) ? CNT_W : 7) + 3;
    wire signed [EW-1:0] next =
          $signed({{(EW-7){1'b0}}, nonblocked})
        + $signed({{(EW-1){1'b0}}, launched})
        + $signed({{(EW-CNT_W){1'b0}}, unblocked})
        - $signed({{(EW-CNT_W){1'b0}}, blocked})
        - $signed({{(EW-CNT_W){1'b0}}, finished});
    assign range_fault = (next < 0) || (next > $signed({{(EW-8){1'b0}}, 8'd127}));

    always @(posedge clk) begin
        if (rst)
            nonblocked <= 7'd0;
        else if (load)
            nonblocked <= next[6:0];
    end
endmodule

// ---------------------------------------------------------------------------
// The WaSP datapath: product = floor(CF x n) with CF = CF_Q / 4, as a
// shift-add of n << i for each set bit i of CF_Q in a 12-bit accumulator,
// then >> 2; real_free = free - product in 11-bit two's complement;
// priority_over_regular = real_free > THRESHOLD (threshold zero-extended).
// CF_VAR = 1 (wasp-m): CF is the input cf_q_var (the meter's register), so
// every partial product stays and the multiplier is a variable one.
module wasp_cf_datapath #(
    parameter integer CF_Q      = 10,
    parameter integer CF_VAR    = 0,
    parameter integer THRESHOLD = 4
) (
`ifdef WASP_CFG_PORTS
    input  wire [4:0]  cfg_cf_q,
    input  wire [4:0]  cfg_threshold,
`else
    // read only when CF_VAR = 1 (wasp-m); tied to 0 otherwise
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [4:0]  cf_q_var,
    /* verilator lint_on UNUSEDSIGNAL */
`endif
    input  wire [4:0]  free_mshrs,
    input  wire [6:0]  nonblocked,
    output wire [9:0]  product,
    output wire [10:0] real_free,
    output wire        priority_over_regular
);
`ifndef WASP_CFG_PORTS
    wire [4:0] cfg_cf_q      = (CF_VAR != 0) ? cf_q_var : CF_Q[4:0];
    wire [4:0] cfg_threshold = THRESHOLD[4:0];
`endif
    wire [11:0] n   = {5'd0, nonblocked};
    wire [11:0] pp0 = cfg_cf_q[0] ? n        : 12'd0;
    wire [11:0] pp1 = cfg_cf_q[1] ? (n << 1) : 12'd0;
    wire [11:0] pp2 = cfg_cf_q[2] ? (n << 2) : 12'd0;
    wire [11:0] pp3 = cfg_cf_q[3] ? (n << 3) : 12'd0;
    wire [11:0] pp4 = cfg_cf_q[4] ? (n << 4) : 12'd0;
    // floor(q n / 4) drops the accumulator's two fraction bits
    /* verilator lint_off UNUSEDSIGNAL */
    wire [11:0] acc = pp0 + pp1 + pp2 + pp3 + pp4;
    /* verilator lint_on UNUSEDSIGNAL */
    assign product = acc[11:2];
    assign real_free = {6'd0, free_mshrs} - {1'b0, product};
    assign priority_over_regular = $signed(real_free) > $signed({6'd0, cfg_threshold});
endmodule

// ---------------------------------------------------------------------------
// The CF meter of wasp-m (cf_meter.rs, beyond the paper): misses per
// launched priority warp, measured over windows of 16 priority launches.
//   acc    <= sat127(acc + misses)          every loading cycle
//   on a launch, the 16th of the window (launches == 15):
//          cf_q <= sat127(acc + misses) >> 2   (quarters of a miss per warp)
//          launches <= 0, acc <= 0
//   on any other launch: launches <= launches + 1
// The sum is 8 bits wide (127 + 3 = 130) and saturates at 127, so the
// accumulator never wraps and acc >> 2 <= 31 always fits the 5-bit CF, the
// datapath's range. Registers load only when `load` (no fault this cycle);
// reset: an empty window, CF = 10 (2.5, the paper's constant).
module wasp_cf_meter (
    input  wire       clk,
    input  wire       rst,
    input  wire       load,
    input  wire       launched,   // a priority warp launched this cycle
    input  wire [1:0] misses,     // primary misses of priority warps this cycle
    output reg  [3:0] launches,
    output reg  [6:0] acc,
    output reg  [4:0] cf_q
);
    wire [7:0] sum        = {1'b0, acc} + {6'd0, misses};
    wire [6:0] acc_sat    = sum[7] ? 7'd127 : sum[6:0];
    wire       window_end = launched && (launches == 4'd15);

    always @(posedge clk) begin
        if (rst) begin
            launches <= 4'd0;
            acc      <= 7'd0;
            cf_q     <= 5'd10;
        end else if (load) begin
            if (window_end) begin
                launches <= 4'd0;
                acc      <= 7'd0;
                cf_q     <= acc_sat[6:2];
            end else begin
                launches <= launches + {3'd0, launched};
                acc      <= acc_sat;
            end
        end
    end
endmodule

// ---------------------------------------------------------------------------
// The launch policy: which FIFO to launch from (0 none, 1 regular,
// 2 priority). POLICY 0 baseline, 1 fullpriority, 2 freemshr-N
// (free_mshrs >= N), 3 wasp and 4 wasp-m (priority_over_regular): the gate
// (prio_allowed). The launch rule: a priority warp if one waits and the gate
// is open, else a regular warp if one waits, else -- a priority warp waits,
// the gate is closed -- LAUNCH_RULE 0 (hold, the paper's: "If the boolean
// evaluates to true, a priority warp (if available) is launched; otherwise,
// a regular warp is launched") launches nothing, 1 (launch,
// work-conserving) launches the priority warp.
module wasp_launch_select #(
    parameter integer POLICY      = 3,
    parameter integer FREEMSHR_N  = 10,
    parameter integer LAUNCH_RULE = 0
) (
`ifdef WASP_CFG_PORTS
    input  wire [2:0] cfg_policy,
    input  wire [4:0] cfg_freemshr_n,
    input  wire       cfg_launch_rule,
`endif
    input  wire       prio_waiting,
    input  wire       reg_waiting,
    input  wire [4:0] free_mshrs,
    input  wire       priority_over_regular,
    input  wire       launch_enable,
    output wire [1:0] select,
    output wire [1:0] launch
);
`ifndef WASP_CFG_PORTS
    wire [2:0] cfg_policy      = POLICY[2:0];
    wire [4:0] cfg_freemshr_n  = FREEMSHR_N[4:0];
    wire       cfg_launch_rule = LAUNCH_RULE[0];
`endif
    wire prio_allowed =
        (cfg_policy == 3'd1) ? 1'b1 :
        (cfg_policy == 3'd2) ? (free_mshrs >= cfg_freemshr_n) :
        (cfg_policy == 3'd3 || cfg_policy == 3'd4) ? priority_over_regular :
                               1'b0;
    assign select = (prio_waiting && prio_allowed)    ? 2'd2 :
                    reg_waiting                       ? 2'd1 :
                    (prio_waiting && cfg_launch_rule) ? 2'd2 :
                                                        2'd0;
    assign launch = launch_enable ? select : 2'd0;
endmodule

// ---------------------------------------------------------------------------
// The launch scheduler of one core. Defaults: the paper's machine (16 MSHRs
// at the L0, a 64-warp input queue, WaSP with CF = 2.5 and threshold 4,
// Mesh4).
module wasp_sched #(
    parameter integer POLICY     = 3,   // 0 baseline, 1 fullpriority, 2 freemshr-N, 3 wasp, 4 wasp-m
    parameter integer CAPACITY   = 16,  // MSHR entries (0..31)
    parameter integer QUEUE_CAP  = 64,  // shared input-queue slots
    parameter integer CF_Q       = 10,  // CF in quarters (0..31): 10 = 2.5 (not read by wasp-m)
    parameter integer THRESHOLD  = 4,   // WaSP threshold (0..31)
    parameter integer FREEMSHR_N = 10,  // FreeMSHR-N's N (0..31)
    parameter integer MESH_BITS  = 2,   // Mesh-k, k = 2**MESH_BITS (1..4)
    parameter integer LAUNCH_RULE = 0,  // gate closed, only priority warps waiting: 0 hold, 1 launch
    parameter integer CNT_W      = 8,   // width of the event counts
    parameter integer OCC_W      = (QUEUE_CAP < 2) ? 1 : $clog2(QUEUE_CAP + 1)
) (
    input  wire             clk,
    input  wire             rst,
`ifdef WASP_CFG_PORTS
    input  wire [2:0]       cfg_policy,
    input  wire [4:0]       cfg_capacity,
    input  wire [4:0]       cfg_cf_q,
    input  wire [4:0]       cfg_threshold,
    input  wire [4:0]       cfg_freemshr_n,
    input  wire [OCC_W-1:0] cfg_queue_cap,
    input  wire             cfg_launch_rule,
`endif
    input  wire             push_valid,
    input  wire [4:0]       qx,
    input  wire [4:0]       qy,
    input  wire             launch_enable,
    input  wire [CNT_W-1:0] mshr_allocs,
    input  wire [CNT_W-1:0] mshr_replies,
    input  wire [CNT_W-1:0] prio_blocked,
    input  wire [CNT_W-1:0] prio_unblocked,
    input  wire [CNT_W-1:0] prio_finished,
    // primary misses of priority warps: read only by wasp-m's CF meter
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [CNT_W-1:0] prio_misses,
    /* verilator lint_on UNUSEDSIGNAL */
    output wire [4:0]       free_mshrs,
    output wire [6:0]       nonblocked,
    output wire [OCC_W-1:0] prio_occ,
    output wire [OCC_W-1:0] reg_occ,
    output wire             is_priority,
    output wire             push_accepted,
    output wire [9:0]       product,
    output wire [10:0]      real_free,
    output wire             priority_over_regular,
    output wire [1:0]       select,
    output wire [1:0]       launch,
    output wire             fault,
    // wasp-m's CF meter (registers, Q; 0 without a meter) and the CF the
    // datapath multiplies by (the meter's register, else CF_Q)
    output wire [3:0]       meter_launches,
    output wire [6:0]       meter_acc,
    output wire [4:0]       cf_q
);
    // Parameter checks: an out-of-range parameter instantiates a module that
    // does not exist, so elaboration stops with its name as the message.
    generate
        if (CAPACITY < 0 || CAPACITY > 31)     wasp_sched_param_error_CAPACITY_must_be_0_to_31 e0 ();
        if (CF_Q < 0 || CF_Q > 31)             wasp_sched_param_error_CF_Q_must_be_0_to_31 e1 ();
        if (THRESHOLD < 0 || THRESHOLD > 31)   wasp_sched_param_error_THRESHOLD_must_be_0_to_31 e2 ();
        if (FREEMSHR_N < 0 || FREEMSHR_N > 31) wasp_sched_param_error_FREEMSHR_N_must_be_0_to_31 e3 ();
        if (MESH_BITS < 1 || MESH_BITS > 4)    wasp_sched_param_error_MESH_BITS_must_be_1_to_4 e4 ();
        if (POLICY < 0 || POLICY > 4)          wasp_sched_param_error_POLICY_must_be_0_to_4 e5 ();
        if (CNT_W < 1)                         wasp_sched_param_error_CNT_W_must_be_positive e6 ();
        if (LAUNCH_RULE < 0 || LAUNCH_RULE > 1) wasp_sched_param_error_LAUNCH_RULE_must_be_0_or_1 e8 ();
        if (QUEUE_CAP < 0 || QUEUE_CAP >= (1 << OCC_W))
                                               wasp_sched_param_error_QUEUE_CAP_must_fit_OCC_W e7 ();
    endgenerate

    wire prio_waiting, reg_waiting;
    wire free_fault, nb_fault;
    assign fault = free_fault || nb_fault;

    wasp_mesh_cmp #(.MESH_BITS(MESH_BITS), .POLICY(POLICY)) u_mesh (
`ifdef WASP_CFG_PORTS
        .cfg_policy(cfg_policy),
`endif
        .qx(qx), .qy(qy), .is_priority(is_priority)
    );

    wasp_split_queue #(.QUEUE_CAP(QUEUE_CAP), .OCC_W(OCC_W)) u_queue (
        .clk(clk), .rst(rst),
`ifdef WASP_CFG_PORTS
        .cfg_queue_cap(cfg_queue_cap),
`endif
        .push_valid(push_valid), .push_priority(is_priority),
        .pop_priority(launch == 2'd2), .pop_regular(launch == 2'd1),
        .prio_occ(prio_occ), .reg_occ(reg_occ),
        .push_accepted(push_accepted),
        .prio_waiting(prio_waiting), .reg_waiting(reg_waiting)
    );

    wasp_free_mshr_reg #(.CAPACITY(CAPACITY), .CNT_W(CNT_W)) u_free (
        .clk(clk), .rst(rst),
`ifdef WASP_CFG_PORTS
        .cfg_capacity(cfg_capacity),
`endif
        .allocs(mshr_allocs), .replies(mshr_replies), .load(!fault),
        .free_mshrs(free_mshrs), .range_fault(free_fault)
    );

    wasp_nonblocked_ctr #(.CNT_W(CNT_W)) u_nonblocked (
        .clk(clk), .rst(rst),
        .launched(launch == 2'd2),
        .blocked(prio_blocked), .unblocked(prio_unblocked), .finished(prio_finished),
        .load(!fault),
        .nonblocked(nonblocked), .range_fault(nb_fault)
    );

    // wasp-m: the CF meter, and the CF the datapath multiplies by. The
    // meter's misses input is 2 bits; larger counts clamp to 3 (as the Rust
    // scheduler clamps them before CfMeter::next).
    localparam [CNT_W+1:0] MISSES_MAX = 3;
`ifdef WASP_CFG_PORTS
    wire [CNT_W+1:0] misses_wide = {2'b00, prio_misses};
    wire [4:0]       meter_cf;
    wasp_cf_meter u_meter (
        .clk(clk), .rst(rst), .load(!fault), .launched(launch == 2'd2),
        .misses((misses_wide > MISSES_MAX) ? 2'd3 : misses_wide[1:0]),
        .launches(meter_launches), .acc(meter_acc), .cf_q(meter_cf)
    );
    assign cf_q = (cfg_policy == 3'd4) ? meter_cf : cfg_cf_q;
`else
    generate
        if (POLICY == 4) begin : g_meter
            wire [CNT_W+1:0] misses_wide = {2'b00, prio_misses};
            wasp_cf_meter u_meter (
                .clk(clk), .rst(rst), .load(!fault), .launched(launch == 2'd2),
                .misses((misses_wide > MISSES_MAX) ? 2'd3 : misses_wide[1:0]),
                .launches(meter_launches), .acc(meter_acc), .cf_q(cf_q)
            );
        end else begin : g_wired_cf
            assign meter_launches = 4'd0;
            assign meter_acc      = 7'd0;
            assign cf_q           = CF_Q[4:0];
        end
    endgenerate
`endif

    wasp_cf_datapath #(.CF_Q(CF_Q), .CF_VAR((POLICY == 4) ? 1 : 0), .THRESHOLD(THRESHOLD)) u_datapath (
`ifdef WASP_CFG_PORTS
        .cfg_cf_q(cf_q), .cfg_threshold(cfg_threshold),
`else
        .cf_q_var(cf_q),
`endif
        .free_mshrs(free_mshrs), .nonblocked(nonblocked),
        .product(product), .real_free(real_free),
        .priority_over_regular(priority_over_regular)
    );

    wasp_launch_select #(.POLICY(POLICY), .FREEMSHR_N(FREEMSHR_N), .LAUNCH_RULE(LAUNCH_RULE)) u_select (
`ifdef WASP_CFG_PORTS
        .cfg_policy(cfg_policy), .cfg_freemshr_n(cfg_freemshr_n),
        .cfg_launch_rule(cfg_launch_rule),
`endif
        .prio_waiting(prio_waiting), .reg_waiting(reg_waiting),
        .free_mshrs(free_mshrs),
        .priority_over_regular(priority_over_regular),
        .launch_enable(launch_enable),
        .select(select), .launch(launch)
    );
endmodule

`default_nettype wire
