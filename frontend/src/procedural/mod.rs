//! Procedural scenes: no download needed. Used by unit tests and as the
//! embedded default. Their names start with `procedural:` so every report
//! says they are not game data.
//!
//! * `procedural:plane` — a 3D scene: a large tiled stone ground plane in
//!   perspective (its 512x512 texture repeats every 8 units, so distant
//!   quads minify and hit deep mip levels), eight crates and brick blocks
//!   and a sky. Every material uses the `standard` shader template (the
//!   default of a lit, textured 3D surface; base texture trilinear, the
//!   sky bilinear) unless the scene definition names another. The scene
//!   also carries baked lightmaps (shadows and ambient occlusion computed
//!   here by casting rays to a directional light) and a second UV set, so
//!   `shader = "lightmapped"` gives a Quake-3-style lit variant
//!   (`scenes/procedural-plane-lit.toml`). Cameras: `ground` (default,
//!   eye height 1.7) and `high` (looking down from 25 units).
//! * `procedural:sprites` — a 2D match-3 puzzle screen under an
//!   orthographic camera: a tiled backdrop, an 8x10 board of opaque cells,
//!   alpha-blended gems (a few falling between cells), a translucent side
//!   panel with a portrait and score digits, and sparkles on top, in
//!   back-to-front (painter's) order. Every material uses the `sprite`
//!   template (bilinear; the pixel font nearest). Camera: `full`.
//!
//! Textures are generated from integer hashes, so a scene is identical on
//! every machine.

use super::def::{Game, SceneDef};
use super::shader;
use super::{
    Blend, Camera, Draw, Filter, Material, Mesh, Scene, SceneError, ShaderOp, Texture, Vec3,
};
use crate::rng::Rng;

mod plane;
mod sprites;
mod synth;

pub use plane::plane;
pub use sprites::sprites;
use synth::*;

/// The procedural maps.
pub const MAPS: [&str; 2] = ["plane", "sprites"];

/// Load a procedural scene from its definition (`game = "procedural"`).
pub fn load(def: &SceneDef) -> Result<Scene, SceneError> {
    let file = format!("scenes/{}.toml", def.name);
    if def.game != Game::Procedural {
        return Err(SceneError::in_file(
            &file,
            format!("game {}: expected procedural", def.game),
        ));
    }
    let mut scene = match def.map.as_str() {
        "plane" => plane(&def.camera, def.shader.as_deref().unwrap_or("standard"))
            .map_err(|e| SceneError::in_file(&file, e.message))?,
        "sprites" => sprites(&def.camera, def.width, def.height)?,
        other => {
            return Err(SceneError::in_file(
                &file,
                format!(
                    "procedural map `{other}` (expected one of {})",
                    MAPS.join(", ")
                ),
            ))
        }
    };
    if let (Some(t), "sprites") = (&def.shader, def.map.as_str()) {
        apply_template(&mut scene, t).map_err(|m| SceneError::in_file(&file, m))?;
    }
    Ok(scene)
}

/// Replace every material's program by the template `name` over the
/// material's first texture (and, for `lightmapped`, its second).
pub fn apply_template(scene: &mut Scene, name: &str) -> Result<(), String> {
    if !shader::TEMPLATES.contains(&name) {
        return Err(format!(
            "shader template `{name}` (expected one of {})",
            shader::TEMPLATES.join(", ")
        ));
    }
    let has_uv2 = scene.meshes.iter().all(|m| m.uv2.is_some());
    for m in &mut scene.materials {
        let tex: Vec<_> = m
            .shader
            .iter()
            .filter_map(|op| match op {
                ShaderOp::Tex(s) => Some(*s),
                ShaderOp::Alu(_) => None,
            })
            .collect();
        let Some(base) = tex.first() else {
            return Err(format!("material {} has no texture", m.name));
        };
        m.shader = match name {
            "standard" => shader::standard(base.texture, base.filter),
            "sprite" => shader::sprite(base.texture, base.filter),
            "unlit" => shader::unlit(base.texture, base.filter),
            _ => {
                let Some(lm) = tex.get(1).filter(|s| s.uv_set == 1) else {
                    return Err(format!(
                        "template lightmapped needs a lightmap; material {} has none",
                        m.name
                    ));
                };
                if !has_uv2 {
                    return Err(format!(
                        "template lightmapped needs a second UV set; {} has none",
                        scene.name
                    ));
                }
                shader::lightmapped(base.texture, lm.texture, base.filter)
            }
        };
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::{rasterize, RasterOptions};

    pub(super) fn def(map: &str, w: u32, h: u32) -> SceneDef {
        SceneDef {
            name: format!("procedural-{map}"),
            ..crate::def::test_def(
                Game::Procedural,
                map,
                if map == "plane" { "ground" } else { "full" },
                w,
                h,
            )
        }
    }

    pub(super) fn no_colour() -> RasterOptions {
        RasterOptions {
            colour: false,
            ..RasterOptions::default()
        }
    }

    #[test]
    fn scenes_are_deterministic() {
        for map in MAPS {
            let d = def(map, 320, 192);
            let a = rasterize(&load(&d).unwrap(), 320, 192, &RasterOptions::default()).unwrap();
            let b = rasterize(&load(&d).unwrap(), 320, 192, &RasterOptions::default()).unwrap();
            assert_eq!(a.trace.to_text(), b.trace.to_text(), "{map}");
            assert_eq!(a.image, b.image, "{map}");
        }
    }

    #[test]
    fn template_override_and_bad_names() {
        let mut d = def("plane", 256, 128);
        let s = load(&d).unwrap();
        assert!(s
            .materials
            .iter()
            .all(|m| shader::mem_ratio(&m.shader) == 1.0 / 11.0));
        d.shader = Some("lightmapped".into());
        let s = load(&d).unwrap();
        assert_eq!(s.name, "procedural:plane:lit");
        assert!(s
            .materials
            .iter()
            .all(|m| shader::mem_ratio(&m.shader) == 2.0 / 14.0));
        let f = rasterize(&s, 256, 128, &no_colour()).unwrap();
        let want = shader::mem_ratio(&shader::lightmapped(0, 1, Filter::Trilinear));
        assert!((f.trace.stats().mem_instr_ratio - want).abs() < 1e-12);
        d.shader = Some("fancy".into());
        assert!(load(&d).unwrap_err().message.contains("fancy"));
        let mut d = def("sprites", 256, 128);
        d.shader = Some("lightmapped".into());
        assert!(load(&d).is_err());
        let mut d = def("nowhere", 256, 128);
        d.map = "nowhere".into();
        assert!(load(&d).unwrap_err().message.contains("plane"));
    }
}
