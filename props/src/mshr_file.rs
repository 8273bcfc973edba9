//! (f) A cache's MSHR file: occupancy never exceeds its capacity, and a
//! cache whose MSHRs are all occupied accepts no access, hits included.
//!
//! The body [`cache_step`] applies one operation to a `wasp_sim` [`Cache`]
//! and to the reference [`CacheModel`] and compares them. The model is the
//! cache's contract written out with unbounded sets instead of arrays: the
//! lines present, the pending misses with their target counts, the entries
//! held in the cycle after their reply, and the ports used this cycle. The
//! domain uses at most as many distinct blocks as the cache has ways in one
//! set, so no line is ever evicted and the model predicts every lookup
//! exactly (hit, primary miss, secondary miss, merge-full, stall, port-busy).
//!
//! Checked after every operation: the lookup equals the model's; a refused
//! access changed nothing (no statistic, no entry, no line); occupancy and
//! outstanding entries equal the model's and occupancy is at most the
//! capacity; a fill hands back exactly the targets that waited; every
//! block's presence and pending state equal the model's.

use crate::cex::{ensure, Cex};
use std::collections::{BTreeMap, BTreeSet};
use wasp_sim::mem::{Cache, CacheConfig, Lookup, MSHR_HOLD_CYCLES};

/// Property name used in counterexamples.
pub const PROP: &str = "(f) MSHR file";

/// Distinct blocks of the domain (at most the ways of [`small_cache`]).
pub const BLOCKS: u64 = 3;

/// One operation on the cache.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CacheOp {
    /// Present an access for the block in the current cycle.
    Access(u64),
    /// The reply for the block arrives in the current cycle (only applied
    /// while a miss for it is pending; otherwise the step is a no-op).
    Fill(u64),
    /// Move to the next cycle.
    Tick,
}

/// Every operation of the domain.
pub const OPS: [CacheOp; 7] = [
    CacheOp::Access(0),
    CacheOp::Access(1),
    CacheOp::Access(2),
    CacheOp::Fill(0),
    CacheOp::Fill(1),
    CacheOp::Fill(2),
    CacheOp::Tick,
];

/// Operation from a code (`code % 7` indexes [`OPS`]).
pub fn op_from_code(code: u8) -> CacheOp {
    OPS[(code % OPS.len() as u8) as usize]
}

/// A one-set, four-way cache (no eviction over [`BLOCKS`] blocks) with
/// `mshrs` entries of `1 + max_merged` targets and `ports` ports.
pub fn small_cache(mshrs: u32, max_merged: u32, ports: u32) -> CacheConfig {
    CacheConfig {
        size_bytes: 256,
        ways: 4,
        line_bytes: 64,
        hit_latency: 1,
        mshrs,
        max_merged,
        ports,
    }
}

/// The reference model of one cache.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CacheModel {
    /// MSHR entries.
    pub capacity: u32,
    /// Targets per entry.
    pub targets: u32,
    /// Ports.
    pub ports: u32,
    /// The current cycle.
    pub now: u64,
    /// Accesses accepted this cycle.
    pub ports_used: u32,
    /// Lines present.
    pub lines: BTreeSet<u64>,
    /// Pending misses: block -> targets recorded.
    pub pending: BTreeMap<u64, u32>,
    /// Entries after their reply: the first cycle each is free again.
    pub held: Vec<u64>,
    /// Next target value handed to the cache (each access a fresh one).
    pub next_target: u32,
    /// Targets recorded per pending block, in order.
    pub waiting: BTreeMap<u64, Vec<u32>>,
}

impl CacheModel {
    /// The model of an empty cache of `cfg` at cycle 0.
    pub fn new(cfg: &CacheConfig) -> Self {
        Self {
            capacity: cfg.mshrs,
            targets: 1 + cfg.max_merged,
            ports: cfg.ports,
            now: 0,
            ports_used: 0,
            lines: BTreeSet::new(),
            pending: BTreeMap::new(),
            held: Vec::new(),
            next_target: 0,
            waiting: BTreeMap::new(),
        }
    }

    /// Entries occupied: pending or held.
    pub fn occupied(&self) -> u32 {
        (self.pending.len() + self.held.len()) as u32
    }

    /// What the cache must answer to an access for `block` now.
    pub fn expect(&self, block: u64) -> Lookup {
        if self.ports_used >= self.ports {
            Lookup::PortBusy
        } else if self.occupied() >= self.capacity {
            Lookup::Stall
        } else if self.lines.contains(&block) {
            Lookup::Hit
        } else if let Some(&n) = self.pending.get(&block) {
            if n < self.targets {
                Lookup::Secondary
            } else {
                Lookup::MergeFull
            }
        } else {
            Lookup::Miss
        }
    }
}

/// What a refused access must leave unchanged.
fn observable(cache: &Cache) -> [u64; 7] {
    let s = cache.stats();
    [
        s.accesses,
        s.hits,
        s.misses,
        s.secondary_misses,
        u64::from(cache.mshr_occupied()),
        u64::from(cache.mshr_outstanding()),
        u64::from(cache.allocated_now()),
    ]
}

fn lookup_code(l: Lookup) -> i64 {
    match l {
        Lookup::Hit => 0,
        Lookup::Miss => 1,
        Lookup::Secondary => 2,
        Lookup::Stall => 3,
        Lookup::MergeFull => 4,
        Lookup::PortBusy => 5,
    }
}

impl CacheModel {
    /// Apply `op` to the model alone; returns the lookup an access gets.
    /// A fill of a block with no pending miss changes nothing.
    pub fn step(&mut self, op: CacheOp) -> Option<Lookup> {
        match op {
            CacheOp::Tick => {
                self.now += 1;
                self.ports_used = 0;
                let now = self.now;
                self.held.retain(|&free_at| free_at > now);
                None
            }
            CacheOp::Access(block) => {
                let got = self.expect(block);
                let target = self.next_target;
                match got {
                    Lookup::Hit => self.ports_used += 1,
                    Lookup::Secondary => {
                        self.ports_used += 1;
                        *self.pending.get_mut(&block).expect("pending") += 1;
                        self.waiting.entry(block).or_default().push(target);
                        self.next_target += 1;
                    }
                    Lookup::Miss => {
                        self.ports_used += 1;
                        self.pending.insert(block, 1);
                        self.waiting.insert(block, vec![target]);
                        self.next_target += 1;
                    }
                    Lookup::Stall | Lookup::MergeFull | Lookup::PortBusy => {}
                }
                Some(got)
            }
            CacheOp::Fill(block) => {
                if self.pending.remove(&block).is_some() {
                    self.waiting.remove(&block);
                    self.lines.insert(block);
                    self.held.push(self.now + 1 + MSHR_HOLD_CYCLES);
                }
                None
            }
        }
    }
}

/// Apply `op` to the cache and the model and compare them (see the module
/// documentation).
pub fn cache_step(cache: &mut Cache, model: &mut CacheModel, op: CacheOp) -> Result<(), Cex> {
    let cap = i64::from(model.capacity);
    match op {
        CacheOp::Tick => {
            model.step(op);
            cache.advance(model.now);
        }
        CacheOp::Access(block) => {
            let full_before = cache.mshr_occupied() >= cache.mshr_capacity();
            let before = observable(cache);
            let (now, target) = (model.now, model.next_target);
            let want = model.step(op).expect("an access has a lookup");
            let got = cache.access(now, block, target);
            let cex = |what| {
                Cex::new(PROP, what)
                    .with("capacity", cap)
                    .with("cycle", now as i64)
                    .with("block", block as i64)
                    .with("expected", lookup_code(want))
                    .with("observed", lookup_code(got))
                    .with("occupied", i64::from(cache.mshr_occupied()))
            };
            ensure(got == want, || cex("lookup differs from the model"))?;
            ensure(!(full_before && got.accepted()), || {
                cex("a cache with every MSHR occupied accepted an access")
            })?;
            if !got.accepted() {
                ensure(observable(cache) == before, || {
                    cex("a refused access changed the cache")
                })?;
            }
        }
        CacheOp::Fill(block) => {
            let Some(want) = model.waiting.get(&block).cloned() else {
                return Ok(());
            };
            model.step(op);
            let got = cache.fill(model.now, block).to_vec();
            ensure(got == want, || {
                Cex::new(PROP, "a fill handed back other targets than waited")
                    .with("block", block as i64)
                    .with("expected", want.len() as i64)
                    .with("observed", got.len() as i64)
            })?;
        }
    }
    let (occ, out) = (cache.mshr_occupied(), cache.mshr_outstanding());
    let cex = |what| {
        Cex::new(PROP, what)
            .with("capacity", cap)
            .with("cycle", model.now as i64)
            .with("occupied", i64::from(occ))
            .with("model_occupied", i64::from(model.occupied()))
            .with("outstanding", i64::from(out))
            .with("model_outstanding", model.pending.len() as i64)
    };
    ensure(occ <= model.capacity, || {
        cex("occupancy exceeds the capacity")
    })?;
    ensure(occ == model.occupied(), || {
        cex("occupancy differs from the model")
    })?;
    ensure(out as usize == model.pending.len(), || {
        cex("outstanding entries differ from the model")
    })?;
    for b in 0..BLOCKS {
        ensure(cache.contains(b) == model.lines.contains(&b), || {
            cex("line presence differs from the model").with("block", b as i64)
        })?;
        ensure(
            cache.is_pending(b) == model.pending.contains_key(&b),
            || cex("pending miss differs from the model").with("block", b as i64),
        )?;
    }
    Ok(())
}

/// Run `ops` from an empty cache of `cfg`.
pub fn cache_sequence(cfg: &CacheConfig, ops: &[CacheOp]) -> Result<(), Cex> {
    let mut cache = Cache::new(cfg).map_err(|_| Cex::new(PROP, "configuration refused"))?;
    let mut model = CacheModel::new(cfg);
    for &op in ops {
        cache_step(&mut cache, &mut model, op)?;
    }
    Ok(())
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;

    /// Depth of the Kani harness.
    const KANI_DEPTH: usize = 5;

    /// Twin: `tests::exhaustive_cache_sequences` (every configuration of
    /// the domain, depth 6).
    #[kani::proof]
    #[kani::unwind(8)]
    fn proof_cache_sequence() {
        let mshrs = u32::from(kani::any_where(|m: &u8| (1..=3).contains(m)));
        let merged = u32::from(kani::any_where(|m: &u8| *m <= 1));
        let ports = u32::from(kani::any_where(|p: &u8| (1..=2).contains(p)));
        let mut ops = [CacheOp::Tick; KANI_DEPTH];
        for op in ops.iter_mut() {
            *op = op_from_code(kani::any_where(|c: &u8| usize::from(*c) < OPS.len()));
        }
        assert!(cache_sequence(&small_cache(mshrs, merged, ports), &ops).is_ok());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Depth of the exhaustive twin: every operation sequence of up to
    /// this many steps.
    pub const DEPTH: usize = 7;

    /// Lookups seen while exploring, to show the domain is not vacuous.
    #[derive(Default)]
    struct Seen {
        steps: u64,
        lookups: BTreeSet<i64>,
        full_refusals: u64,
    }

    fn explore(
        cache: &Cache,
        model: &CacheModel,
        depth: usize,
        path: &mut Vec<CacheOp>,
        seen: &mut Seen,
    ) {
        if depth == DEPTH {
            return;
        }
        for op in OPS {
            if let CacheOp::Fill(b) = op {
                if !model.pending.contains_key(&b) {
                    continue;
                }
            }
            let (mut c, mut m) = (cache.clone(), model.clone());
            path.push(op);
            let full = m.occupied() >= m.capacity && m.ports_used < m.ports;
            if let Err(e) = cache_step(&mut c, &mut m, op) {
                panic!("{e}\nsequence: {path:?}");
            }
            seen.steps += 1;
            if let CacheOp::Access(b) = op {
                seen.lookups.insert(lookup_code(model.expect(b)));
                seen.full_refusals += u64::from(full);
            }
            explore(&c, &m, depth + 1, path, seen);
            path.pop();
        }
    }

    #[test]
    fn exhaustive_cache_sequences() {
        let mut seen = Seen::default();
        for mshrs in 1..=3 {
            for merged in 0..=1 {
                for ports in 1..=2 {
                    let cfg = small_cache(mshrs, merged, ports);
                    let cache = Cache::new(&cfg).unwrap();
                    explore(
                        &cache,
                        &CacheModel::new(&cfg),
                        0,
                        &mut Vec::new(),
                        &mut seen,
                    );
                }
            }
        }
        // Every kind of lookup occurs, and full files were tried.
        assert_eq!(seen.lookups.len(), 6, "lookups seen: {:?}", seen.lookups);
        assert!(seen.full_refusals > 1000, "{}", seen.full_refusals);
        assert_eq!(seen.steps, 798_282);
    }

    #[test]
    fn a_full_file_refuses_a_hit() {
        // One entry: miss on 0, fill it (held through the next cycle), miss
        // on 1; the file is full, so the access to the present line 0 stalls.
        let cfg = small_cache(1, 0, 2);
        let ops = [
            CacheOp::Access(0),
            CacheOp::Fill(0),
            CacheOp::Tick,
            CacheOp::Tick,
            CacheOp::Access(1),
            CacheOp::Tick,
        ];
        let mut cache = Cache::new(&cfg).unwrap();
        let mut model = CacheModel::new(&cfg);
        for op in ops {
            cache_step(&mut cache, &mut model, op).unwrap();
        }
        assert!(cache.contains(0));
        assert_eq!(cache.access(model.now, 0, 99), Lookup::Stall);
    }

    #[test]
    fn the_model_catches_a_cache_that_ignores_fullness() {
        // A stand-in for a broken cache: the model says Stall, so a cache
        // answering Hit would be caught. Feed the body a model that thinks
        // the file is empty while the cache is full.
        let cfg = small_cache(1, 0, 1);
        let mut cache = Cache::new(&cfg).unwrap();
        let mut model = CacheModel::new(&cfg);
        cache_step(&mut cache, &mut model, CacheOp::Access(0)).unwrap();
        let mut stale = CacheModel::new(&cfg);
        stale.now = model.now;
        let e = cache_step(&mut cache, &mut stale, CacheOp::Tick).unwrap_err();
        assert_eq!(e.property(), PROP);
        assert_eq!(e.what(), "occupancy differs from the model");
    }
}
