// tb_cosim.v -- co-simulation testbench for wasp_sched (props/tests/cosim.rs).
//
// Reads one stimulus line per cycle from +stim=<file>:
//   rst push_valid qx qy launch_enable allocs replies blocked unblocked finished
//   misses
// (decimal). For each line with rst = 0 it writes one line to +out=<file>,
// sampled after the inputs settle and before the clock edge:
//   free_mshrs nonblocked prio_occ reg_occ is_priority push_accepted
//   product real_free priority_over_regular select launch fault
//   meter_launches meter_acc cf_q
// (real_free signed). A line with rst = 1 resets the block (one clock edge)
// and writes nothing. The last line written is "END <cycles>".
//
// The block's parameters are this module's parameters: set them with
// iverilog -P tb_cosim.<NAME>=<value>.

`default_nettype none

module tb_cosim;
    parameter integer POLICY     = 3;
    parameter integer CAPACITY   = 16;
    parameter integer QUEUE_CAP  = 64;
    parameter integer CF_Q       = 10;
    parameter integer THRESHOLD  = 4;
    parameter integer FREEMSHR_N = 10;
    parameter integer MESH_BITS  = 2;
    parameter integer LAUNCH_RULE = 0;
    localparam integer OCC_W = (QUEUE_CAP < 2) ? 1 : $clog2(QUEUE_CAP + 1);

    reg        clk = 1'b0;
    reg        rst = 1'b1;
    reg        push_valid = 1'b0;
    reg  [4:0] qx = 5'd0;
    reg  [4:0] qy = 5'd0;
    reg        launch_enable = 1'b0;
    reg  [7:0] mshr_allocs = 8'd0;
    reg  [7:0] mshr_replies = 8'd0;
    reg  [7:0] prio_blocked = 8'd0;
    reg  [7:0] prio_unblocked = 8'd0;
    reg  [7:0] prio_finished = 8'd0;
    reg  [7:0] prio_misses = 8'd0;

    wire [4:0]       free_mshrs;
    wire [6:0]       nonblocked;
    wire [OCC_W-1:0] prio_occ;
    wire [OCC_W-1:0] reg_occ;
    wire             is_priority;
    wire             push_accepted;
    wire [9:0]       product;
    wire [10:0]      real_free;
    wire             priority_over_regular;
    wire [1:0]       select;
    wire [1:0]       launch;
    wire             fault;
    wire [3:0]       meter_launches;
    wire [6:0]       meter_acc;
    wire [4:0]       cf_q;

    wasp_sched #(
        .POLICY(POLICY), .CAPACITY(CAPACITY), .QUEUE_CAP(QUEUE_CAP),
        .CF_Q(CF_Q), .THRESHOLD(THRESHOLD), .FREEMSHR_N(FREEMSHR_N),
        .LAUNCH_RULE(LAUNCH_RULE),
        .MESH_BITS(MESH_BITS), .CNT_W(8)
    ) dut (
        .clk(clk), .rst(rst),
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

    reg [8*1024-1:0] stim_path;
    reg [8*1024-1:0] out_path;
    integer fin, fout, n, cycles;
    integer i_rst, i_push, i_qx, i_qy, i_en, i_alloc, i_reply, i_blk, i_unblk, i_fin, i_miss;

    initial begin
        if (!$value$plusargs("stim=%s", stim_path) || !$value$plusargs("out=%s", out_path)) begin
            $display("tb_cosim: ERROR: need +stim=<file> +out=<file>");
            $finish;
        end
        fin = $fopen(stim_path, "r");
        fout = $fopen(out_path, "w");
        if (fin == 0 || fout == 0) begin
            $display("tb_cosim: ERROR: cannot open the stimulus or output file");
            $finish;
        end
        cycles = 0;
        n = $fscanf(fin, "%d %d %d %d %d %d %d %d %d %d %d\n",
                    i_rst, i_push, i_qx, i_qy, i_en, i_alloc, i_reply, i_blk, i_unblk, i_fin, i_miss);
        while (n == 11) begin
            rst            = i_rst[0];
            push_valid     = i_push[0];
            qx             = i_qx[4:0];
            qy             = i_qy[4:0];
            launch_enable  = i_en[0];
            mshr_allocs    = i_alloc[7:0];
            mshr_replies   = i_reply[7:0];
            prio_blocked   = i_blk[7:0];
            prio_unblocked = i_unblk[7:0];
            prio_finished  = i_fin[7:0];
            prio_misses    = i_miss[7:0];
            #1;
            if (!rst) begin
                $fwrite(fout, "%0d %0d %0d %0d %0d %0d %0d %0d %0d %0d %0d %0d %0d %0d %0d\n",
                        free_mshrs, nonblocked, prio_occ, reg_occ,
                        is_priority, push_accepted,
                        product, $signed(real_free), priority_over_regular,
                        select, launch, fault,
                        meter_launches, meter_acc, cf_q);
                cycles = cycles + 1;
            end
            clk = 1'b1;
            #1;
            clk = 1'b0;
            #1;
            n = $fscanf(fin, "%d %d %d %d %d %d %d %d %d %d %d\n",
                        i_rst, i_push, i_qx, i_qy, i_en, i_alloc, i_reply, i_blk, i_unblk, i_fin, i_miss);
        end
        $fwrite(fout, "END %0d\n", cycles);
        $fclose(fin);
        $fclose(fout);
        $finish;
    end
endmodule

`default_nettype wire
