//! (e) Mesh-k selects exactly 1/k^2 of a 32 x 32-quad tile: the quads whose
//! low log2(k) bits of x and y are zero; every other paper subset selects
//! 1/16 of the tile.

use crate::cex::{ensure, Cex};
use wasp_rtl::subset::{
    HorizontalLines, Mesh, PrioritySubset, Random, SubsetSpec, Top, VerticalLines,
};

/// Property name used in counterexamples.
pub const PROP: &str = "(e) priority subsets";

/// Quads along one side of a 64 x 64-pixel tile.
pub const TILE_QUADS: u32 = 32;

/// The Mesh sizes the paper evaluates.
pub const MESH_KS: [u32; 4] = [2, 4, 8, 16];

/// Seeds the random-subset checks use.
pub const RANDOM_SEEDS: [u64; 7] = [0, 1, 2, 7, 42, 0x5eed_cafe, u64::MAX];

/// (e), one quad: for `k` in {2, 4, 8, 16} and in-tile coordinates
/// `x, y < 32`, Mesh-k selects the quad iff the low log2(k) bits of `x` and
/// of `y` are zero. (`Ok` for other `k` or coordinates.)
pub fn mesh_quad_exact(k: u32, x: u32, y: u32) -> Result<(), Cex> {
    if !MESH_KS.contains(&k) || x >= TILE_QUADS || y >= TILE_QUADS {
        return Ok(());
    }
    let cex = |what| {
        Cex::new(PROP, what)
            .with("k", k as i64)
            .with("x", x as i64)
            .with("y", y as i64)
    };
    let m = match Mesh::new(k) {
        Some(m) => m,
        None => return Err(cex("Mesh::new refuses a paper k")),
    };
    ensure(m.k() == k && (1 << m.comparator_bits()) == k, || {
        cex("comparator width is not log2(k)")
    })?;
    let low = k - 1;
    let want = x & low == 0 && y & low == 0;
    let got = m.is_priority(x, y);
    ensure(got == want, || {
        cex("Mesh-k selection differs from the low-bits-zero rule")
            .with("expected", want as i64)
            .with("got", got as i64)
    })
}

/// Quads of a 32 x 32 tile `s` selects.
pub fn count_in_tile(s: &dyn PrioritySubset) -> u32 {
    let mut n = 0;
    for y in 0..TILE_QUADS {
        for x in 0..TILE_QUADS {
            n += s.is_priority(x, y) as u32;
        }
    }
    n
}

/// (e), Mesh-k: exactly `1024 / k^2` quads of a 32 x 32 tile, and
/// `size_ratio(32) == 1 / k^2`. Every quad is also checked against the
/// low-bits rule.
pub fn mesh_selects_one_over_k_squared(k: u32) -> Result<(), Cex> {
    let cex = |what| Cex::new(PROP, what).with("k", k as i64);
    let m = match Mesh::new(k) {
        Some(m) => m,
        None => return Err(cex("Mesh::new refuses k")),
    };
    for y in 0..TILE_QUADS {
        for x in 0..TILE_QUADS {
            mesh_quad_exact(k, x, y)?;
        }
    }
    let n = count_in_tile(&m);
    let want = TILE_QUADS * TILE_QUADS / (k * k);
    ensure(n == want, || {
        cex("Mesh-k does not select 1/k^2 of the tile")
            .with("expected", want as i64)
            .with("got", n as i64)
    })?;
    ensure(m.size_ratio(TILE_QUADS) == 1.0 / (k * k) as f64, || {
        cex("size_ratio(32) is not 1/k^2")
    })
}

/// (e), any subset: exactly 64 of the 1024 quads of a 32 x 32 tile (1/16),
/// and `size_ratio(32) == 1/16`.
pub fn selects_one_sixteenth(s: &dyn PrioritySubset) -> Result<(), Cex> {
    let n = count_in_tile(s);
    ensure(n == TILE_QUADS * TILE_QUADS / 16, || {
        Cex::new(PROP, "subset does not select 1/16 of the tile")
            .with("expected", 64)
            .with("got", n as i64)
    })?;
    ensure(s.size_ratio(TILE_QUADS) == 1.0 / 16.0, || {
        Cex::new(PROP, "size_ratio(32) is not 1/16")
    })
}

/// Every 1/16 subset of the paper, built directly and through
/// [`SubsetSpec::build`], with the random subset for each of
/// [`RANDOM_SEEDS`].
pub fn sixteenth_subsets() -> Vec<(String, Box<dyn PrioritySubset>)> {
    let mut v: Vec<(String, Box<dyn PrioritySubset>)> = vec![
        ("mesh4".into(), Box::new(Mesh::new(4).expect("mesh4"))),
        ("hlines".into(), Box::new(HorizontalLines::new(TILE_QUADS))),
        ("vlines".into(), Box::new(VerticalLines::new(TILE_QUADS))),
        ("top16".into(), Box::new(Top::new(TILE_QUADS, 16))),
    ];
    for seed in RANDOM_SEEDS {
        v.push((
            format!("random:{seed}"),
            Box::new(Random::new(TILE_QUADS, 16, seed)),
        ));
    }
    for spec in [
        SubsetSpec::Mesh(4),
        SubsetSpec::HorizontalLines,
        SubsetSpec::VerticalLines,
        SubsetSpec::Top16,
    ]
    .into_iter()
    .chain(RANDOM_SEEDS.into_iter().map(SubsetSpec::Random))
    {
        v.push((format!("spec {spec}"), spec.build(TILE_QUADS)));
    }
    v
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;

    /// Twin: `tests::exhaustive_mesh`. Per-quad rule for a symbolic quad;
    /// the count follows: `x < 32` has `32 / k` values with its low
    /// log2(k) bits zero, so the rule selects `(32 / k)^2 = 1024 / k^2`.
    #[kani::proof]
    #[kani::unwind(6)]
    fn proof_mesh_quad_exact() {
        let sel: u8 = kani::any_where(|s: &u8| *s < 4);
        let k = MESH_KS[sel as usize];
        let x: u8 = kani::any_where(|x: &u8| *x < 32);
        let y: u8 = kani::any_where(|y: &u8| *y < 32);
        assert!(mesh_quad_exact(k, x as u32, y as u32).is_ok());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cex::check;

    /// k in {2, 4, 8, 16}: every quad of the tile and the count; no other
    /// k in 0..=64 builds a Mesh.
    #[test]
    fn exhaustive_mesh() {
        for k in MESH_KS {
            check(mesh_selects_one_over_k_squared(k));
        }
        for k in 0..=64 {
            assert_eq!(Mesh::new(k).is_some(), MESH_KS.contains(&k), "k={k}");
        }
    }

    /// hlines, vlines, top16, mesh4 and random with seven seeds, built
    /// directly and from their specs.
    #[test]
    fn exhaustive_sixteenths() {
        let subsets = sixteenth_subsets();
        assert_eq!(subsets.len(), 2 * (4 + RANDOM_SEEDS.len()));
        for (name, s) in &subsets {
            if let Err(c) = selects_one_sixteenth(s.as_ref()) {
                panic!("{name}: {c}");
            }
        }
    }
}
