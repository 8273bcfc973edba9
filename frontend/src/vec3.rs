//! Three-component vector arithmetic on [`Vec3`] for the scene loaders.

use super::Vec3;

/// `a - b`.
pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a + b`.
pub(crate) fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a * s`.
pub(crate) fn scale(a: Vec3, s: f32) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Euclidean length.
pub(crate) fn len(a: Vec3) -> f32 {
    dot(a, a).sqrt()
}

/// `a` scaled to length 1; +z for a (near) zero vector.
pub(crate) fn normalize(a: Vec3) -> Vec3 {
    let l = len(a);
    if l > 1e-12 {
        scale(a, 1.0 / l)
    } else {
        [0.0, 0.0, 1.0]
    }
}

/// `a x b`.
pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a . b`.
pub(crate) fn dot(a: Vec3, b: Vec3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basics() {
        let (x, y) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        assert_eq!(cross(x, y), [0.0, 0.0, 1.0]);
        assert_eq!(dot(x, y), 0.0);
        assert_eq!(add(x, y), [1.0, 1.0, 0.0]);
        assert_eq!(sub(x, y), [1.0, -1.0, 0.0]);
        assert_eq!(len([3.0, 4.0, 0.0]), 5.0);
        assert_eq!(normalize([0.0, 0.0, 0.0]), [0.0, 0.0, 1.0]);
        assert_eq!(normalize([0.0, 2.0, 0.0]), [0.0, 1.0, 0.0]);
        assert_eq!(scale(y, 3.0), [0.0, 3.0, 0.0]);
    }
}
