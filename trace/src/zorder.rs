//! The order in which a frame's tiles are rendered and appear in a trace:
//! Z-order (Morton order), as the paper's tile fetcher traverses them.

/// Tile coordinates of a `tiles_x` x `tiles_y` grid in Z-order (Morton
/// order: x in the even bits, y in the odd bits of the key).
pub fn z_order(tiles_x: u32, tiles_y: u32) -> Vec<(u32, u32)> {
    let mut v: Vec<(u32, u32)> = (0..tiles_y)
        .flat_map(|y| (0..tiles_x).map(move |x| (x, y)))
        .collect();
    v.sort_by_key(|&(x, y)| morton(x, y));
    v
}

/// The Morton key of (x, y): the bits of x in the even positions, of y in
/// the odd ones.
pub fn morton(x: u32, y: u32) -> u64 {
    fn spread(v: u32) -> u64 {
        let mut v = u64::from(v);
        v = (v | (v << 16)) & 0x0000_ffff_0000_ffff;
        v = (v | (v << 8)) & 0x00ff_00ff_00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333_3333_3333;
        v = (v | (v << 1)) & 0x5555_5555_5555_5555;
        v
    }
    spread(x) | (spread(y) << 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_order_of_a_grid() {
        assert_eq!(z_order(2, 2), vec![(0, 0), (1, 0), (0, 1), (1, 1)]);
        let z = z_order(3, 3);
        assert_eq!(
            z,
            vec![
                (0, 0),
                (1, 0),
                (0, 1),
                (1, 1),
                (2, 0),
                (2, 1),
                (0, 2),
                (1, 2),
                (2, 2)
            ]
        );
    }
}
