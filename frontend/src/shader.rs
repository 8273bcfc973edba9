//! Shader templates: the instruction mix of a material's fragment shader.
//!
//! wasp's own choices (the paper's shaders are not published), set once
//! for every scene: interpolation and setup ALU work before the first
//! texture instruction, lighting/blending ALU work after it. The resulting
//! memory-instruction ratios (texture instructions / all instructions) sit
//! inside the paper's Table I range 0.07-0.26:
//!
//! | template | program | ratio |
//! |---|---|---|
//! | `standard` | a4 T(base) a6 | 1/11 = 0.091 |
//! | `lightmapped` | a4 T(base) a2 T(lightmap) a6 | 2/14 = 0.143 |
//! | `sprite` | a2 T(sprite) a3 | 1/6 = 0.167 |
//! | `unlit` | a2 T(base) a2 | 1/5 = 0.2 |

use super::{Filter, ShaderOp, TexSample};

/// Names of the templates.
pub const TEMPLATES: [&str; 4] = ["standard", "lightmapped", "sprite", "unlit"];

/// A lit, textured 3D surface: one base texture.
pub fn standard(base: usize, filter: Filter) -> Vec<ShaderOp> {
    vec![
        ShaderOp::Alu(4),
        ShaderOp::Tex(TexSample::new(base, 0, filter)),
        ShaderOp::Alu(6),
    ]
}

/// A base texture modulated by a lightmap through the second UV set
/// (Quake 3 surfaces).
pub fn lightmapped(base: usize, lightmap: usize, filter: Filter) -> Vec<ShaderOp> {
    vec![
        ShaderOp::Alu(4),
        ShaderOp::Tex(TexSample::new(base, 0, filter)),
        ShaderOp::Alu(2),
        ShaderOp::Tex(TexSample::new(lightmap, 1, Filter::Bilinear)),
        ShaderOp::Alu(6),
    ]
}

/// A 2D sprite or tile: one texture, little arithmetic.
pub fn sprite(tex: usize, filter: Filter) -> Vec<ShaderOp> {
    vec![
        ShaderOp::Alu(2),
        ShaderOp::Tex(TexSample::new(tex, 0, filter)),
        ShaderOp::Alu(3),
    ]
}

/// An unlit textured surface (sky, UI backgrounds).
pub fn unlit(base: usize, filter: Filter) -> Vec<ShaderOp> {
    vec![
        ShaderOp::Alu(2),
        ShaderOp::Tex(TexSample::new(base, 0, filter)),
        ShaderOp::Alu(2),
    ]
}

/// The memory-instruction ratio of a program.
pub fn mem_ratio(program: &[ShaderOp]) -> f64 {
    let (mut tex, mut all) = (0u64, 0u64);
    for op in program {
        match op {
            ShaderOp::Alu(n) => all += *n as u64,
            ShaderOp::Tex(_) => {
                tex += 1;
                all += 1;
            }
        }
    }
    if all == 0 {
        0.0
    } else {
        tex as f64 / all as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratios_match_the_table() {
        assert!((mem_ratio(&standard(0, Filter::Bilinear)) - 1.0 / 11.0).abs() < 1e-12);
        assert!((mem_ratio(&lightmapped(0, 1, Filter::Trilinear)) - 2.0 / 14.0).abs() < 1e-12);
        assert!((mem_ratio(&sprite(0, Filter::Nearest)) - 1.0 / 6.0).abs() < 1e-12);
        assert!((mem_ratio(&unlit(0, Filter::Bilinear)) - 0.2).abs() < 1e-12);
    }
}
