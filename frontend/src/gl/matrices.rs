//! The fixed-function matrices: modelview, projection and one texture
//! matrix per texture unit, each a stack (load, multiply, push, pop,
//! identity, ortho, frustum, translate, rotate, scale), and the current
//! matrix mode.

use super::enums as gl;

/// A 4x4 matrix, column-major as OpenGL stores it: element (row r,
/// column c) at `c * 4 + r`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat4(pub [f64; 16]);

impl Mat4 {
    /// The identity.
    pub const IDENTITY: Mat4 = Mat4([
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ]);

    /// From rows (as a matrix is written on paper).
    pub fn from_rows(r: [[f64; 4]; 4]) -> Mat4 {
        let mut m = [0.0; 16];
        for (row, v) in r.iter().enumerate() {
            for (col, x) in v.iter().enumerate() {
                m[col * 4 + row] = *x;
            }
        }
        Mat4(m)
    }

    /// Element at (row, column).
    pub fn at(&self, row: usize, col: usize) -> f64 {
        self.0[col * 4 + row]
    }

    /// `self * o`.
    pub fn mul(&self, o: &Mat4) -> Mat4 {
        let mut m = [0.0; 16];
        for c in 0..4 {
            for r in 0..4 {
                m[c * 4 + r] = (0..4).map(|k| self.at(r, k) * o.at(k, c)).sum();
            }
        }
        Mat4(m)
    }

    /// `self * (x, y, z, w)`.
    pub fn apply(&self, p: [f64; 4]) -> [f64; 4] {
        let mut o = [0.0; 4];
        for (r, v) in o.iter_mut().enumerate() {
            *v = (0..4).map(|k| self.at(r, k) * p[k]).sum();
        }
        o
    }

    /// glOrtho's matrix.
    pub fn ortho(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Mat4 {
        Mat4::from_rows([
            [2.0 / (r - l), 0.0, 0.0, -(r + l) / (r - l)],
            [0.0, 2.0 / (t - b), 0.0, -(t + b) / (t - b)],
            [0.0, 0.0, -2.0 / (f - n), -(f + n) / (f - n)],
            [0.0, 0.0, 0.0, 1.0],
        ])
    }

    /// glFrustum's matrix.
    pub fn frustum(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> Mat4 {
        Mat4::from_rows([
            [2.0 * n / (r - l), 0.0, (r + l) / (r - l), 0.0],
            [0.0, 2.0 * n / (t - b), (t + b) / (t - b), 0.0],
            [0.0, 0.0, -(f + n) / (f - n), -2.0 * f * n / (f - n)],
            [0.0, 0.0, -1.0, 0.0],
        ])
    }

    /// glTranslate's matrix.
    pub fn translate(x: f64, y: f64, z: f64) -> Mat4 {
        Mat4::from_rows([
            [1.0, 0.0, 0.0, x],
            [0.0, 1.0, 0.0, y],
            [0.0, 0.0, 1.0, z],
            [0.0, 0.0, 0.0, 1.0],
        ])
    }

    /// glScale's matrix.
    pub fn scale(x: f64, y: f64, z: f64) -> Mat4 {
        Mat4::from_rows([
            [x, 0.0, 0.0, 0.0],
            [0.0, y, 0.0, 0.0],
            [0.0, 0.0, z, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ])
    }

    /// glRotate's matrix: `deg` degrees about (x, y, z) (normalized; a
    /// zero axis is the identity).
    pub fn rotate(deg: f64, x: f64, y: f64, z: f64) -> Mat4 {
        let len = (x * x + y * y + z * z).sqrt();
        if len == 0.0 || !len.is_finite() {
            return Mat4::IDENTITY;
        }
        let (x, y, z) = (x / len, y / len, z / len);
        let (s, c) = deg.to_radians().sin_cos();
        let k = 1.0 - c;
        Mat4::from_rows([
            [x * x * k + c, x * y * k - z * s, x * z * k + y * s, 0.0],
            [y * x * k + z * s, y * y * k + c, y * z * k - x * s, 0.0],
            [x * z * k - y * s, y * z * k + x * s, z * z * k + c, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ])
    }
}

/// A matrix stack: the current matrix is the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Stack(Vec<Mat4>);

impl Default for Stack {
    fn default() -> Self {
        Stack(vec![Mat4::IDENTITY])
    }
}

impl Stack {
    /// The current matrix.
    pub fn top(&self) -> &Mat4 {
        self.0.last().expect("a stack is never empty")
    }

    fn top_mut(&mut self) -> &mut Mat4 {
        self.0.last_mut().expect("a stack is never empty")
    }
}

/// Which stack glMatrixMode selected.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// GL_MODELVIEW.
    ModelView,
    /// GL_PROJECTION.
    Projection,
    /// GL_TEXTURE (of the active texture unit).
    Texture,
}

/// The matrix state: the stacks and the mode.
#[derive(Clone, Debug, PartialEq)]
pub struct Matrices {
    /// GL_MODELVIEW.
    pub modelview: Stack,
    /// GL_PROJECTION.
    pub projection: Stack,
    /// GL_TEXTURE, per texture unit.
    pub texture: Vec<Stack>,
    /// The current mode.
    pub mode: Mode,
}

/// Deepest stack the importer allows (GL guarantees 32 modelview and 2
/// projection and texture entries; deeper is accepted up to this).
const MAX_DEPTH: usize = 256;

impl Matrices {
    /// The initial state: identities, modelview mode, `units` texture
    /// units.
    pub fn new(units: usize) -> Self {
        Self {
            modelview: Stack::default(),
            projection: Stack::default(),
            texture: vec![Stack::default(); units],
            mode: Mode::ModelView,
        }
    }

    /// Select the stack of `mode` (a GL enum); `Err` names what is allowed.
    pub fn set_mode(&mut self, mode: i64) -> Result<(), String> {
        self.mode = match mode {
            gl::MODELVIEW => Mode::ModelView,
            gl::PROJECTION => Mode::Projection,
            gl::TEXTURE => Mode::Texture,
            _ => {
                return Err(format!(
                    "matrix mode {}: expected GL_MODELVIEW, GL_PROJECTION or GL_TEXTURE",
                    gl::name(mode)
                ))
            }
        };
        Ok(())
    }

    fn current(&mut self, unit: usize) -> &mut Stack {
        match self.mode {
            Mode::ModelView => &mut self.modelview,
            Mode::Projection => &mut self.projection,
            Mode::Texture => &mut self.texture[unit],
        }
    }

    /// Replace the current matrix (active texture unit `unit`).
    pub fn load(&mut self, unit: usize, m: Mat4) {
        *self.current(unit).top_mut() = m;
    }

    /// Multiply the current matrix by `m` on the right.
    pub fn mult(&mut self, unit: usize, m: &Mat4) {
        let top = self.current(unit).top_mut();
        *top = top.mul(m);
    }

    /// Push a copy of the current matrix.
    pub fn push(&mut self, unit: usize) -> Result<(), String> {
        let s = self.current(unit);
        if s.0.len() >= MAX_DEPTH {
            return Err(format!("matrix stack overflow (depth {MAX_DEPTH})"));
        }
        let top = *s.top();
        s.0.push(top);
        Ok(())
    }

    /// Pop the current stack.
    pub fn pop(&mut self, unit: usize) -> Result<(), String> {
        let s = self.current(unit);
        if s.0.len() == 1 {
            return Err("matrix stack underflow (glPopMatrix with nothing pushed)".into());
        }
        s.0.pop();
        Ok(())
    }

    /// Projection times modelview: object to clip space.
    pub fn mvp(&self) -> Mat4 {
        self.projection.top().mul(self.modelview.top())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Mat4, b: &Mat4) -> bool {
        a.0.iter().zip(&b.0).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn ortho_and_frustum_map_their_boxes_to_the_unit_cube() {
        // glOrtho(0, 128, 0, 96, -1, 1): (64, 48) is the centre; (128, 96)
        // the top-right corner; z = 1 (eye) is the far plane's -1 ... GL:
        // z_eye = -near maps to -1.
        let o = Mat4::ortho(0.0, 128.0, 0.0, 96.0, -1.0, 1.0);
        assert_eq!(o.apply([64.0, 48.0, 0.0, 1.0]), [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(o.apply([128.0, 96.0, 1.0, 1.0]), [1.0, 1.0, -1.0, 1.0]);
        // glFrustum(-1, 1, -1, 1, 1, 10): a point on the near plane at the
        // right edge -> x_ndc = 1, z_ndc = -1; on the far plane z_ndc = 1.
        let f = Mat4::frustum(-1.0, 1.0, -1.0, 1.0, 1.0, 10.0);
        let p = f.apply([1.0, 0.0, -1.0, 1.0]);
        assert_eq!(p, [1.0, 0.0, -1.0, 1.0]);
        let q = f.apply([0.0, 0.0, -10.0, 1.0]);
        assert!((q[2] / q[3] - 1.0).abs() < 1e-12 && q[3] == 10.0);
    }

    #[test]
    fn translate_rotate_scale_compose_as_gl_does() {
        // Rotating (1, 0, 0) by 90 degrees about z gives (0, 1, 0).
        let r = Mat4::rotate(90.0, 0.0, 0.0, 2.0);
        let p = r.apply([1.0, 0.0, 0.0, 1.0]);
        assert!((p[0]).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12);
        // GL post-multiplies: translate then scale applies the scale first.
        let mut m = Matrices::new(2);
        m.mult(0, &Mat4::translate(10.0, 0.0, 0.0));
        m.mult(0, &Mat4::scale(2.0, 3.0, 4.0));
        assert_eq!(
            m.modelview.top().apply([1.0, 1.0, 1.0, 1.0]),
            [12.0, 3.0, 4.0, 1.0]
        );
        let want = Mat4::from_rows([
            [2.0, 0.0, 0.0, 10.0],
            [0.0, 3.0, 0.0, 0.0],
            [0.0, 0.0, 4.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]);
        assert!(close(m.modelview.top(), &want));
        assert_eq!(Mat4::rotate(30.0, 0.0, 0.0, 0.0), Mat4::IDENTITY);
    }

    #[test]
    fn stacks_push_pop_and_keep_one_texture_matrix_per_unit() {
        let mut m = Matrices::new(2);
        m.set_mode(gl::TEXTURE).unwrap();
        m.load(1, Mat4::scale(2.0, 2.0, 1.0));
        assert_eq!(m.texture[0].top(), &Mat4::IDENTITY);
        assert_eq!(m.texture[1].top().at(0, 0), 2.0);
        m.set_mode(gl::PROJECTION).unwrap();
        m.push(0).unwrap();
        m.load(0, Mat4::translate(1.0, 2.0, 3.0));
        assert_eq!(m.mvp().at(1, 3), 2.0);
        m.pop(0).unwrap();
        assert_eq!(m.mvp(), Mat4::IDENTITY);
        let err = m.pop(0).unwrap_err();
        assert!(err.contains("underflow"), "{err}");
        assert!(m.set_mode(0x1234).unwrap_err().contains("GL_MODELVIEW"));
    }
}
