//! The scene's checks before the front end runs: texture sizes, material
//! programs and the meshes' references (materials, UVs, clip-space w,
//! indices, draw calls), so the pipeline cannot index out of range.

use super::*;
use crate::{Material, Mesh};

/// Checks the scene's references so the pipeline cannot index out of range.
pub(super) fn validate(scene: &Scene) -> Result<(), SceneError> {
    let err = |m: String| SceneError::in_file(&scene.name, m);
    for (i, t) in scene.textures.iter().enumerate() {
        if t.width == 0 || t.height == 0 || t.rgba.len() != t.width as usize * t.height as usize * 4
        {
            return Err(err(format!(
                "texture {i} ({}): {}x{} with {} bytes (expected width x height x 4 > 0)",
                t.name,
                t.width,
                t.height,
                t.rgba.len()
            )));
        }
    }
    for (i, m) in scene.materials.iter().enumerate() {
        validate_material(scene, i, m).map_err(err)?;
    }
    for (i, m) in scene.meshes.iter().enumerate() {
        validate_mesh(scene, i, m).map_err(err)?;
    }
    Ok(())
}

/// Material `i`: a program that does something, sampling textures that
/// exist through UV set 0 or 1.
fn validate_material(scene: &Scene, i: usize, m: &Material) -> Result<(), String> {
    if m.shader.is_empty() || m.shader.iter().all(|op| matches!(op, ShaderOp::Alu(0))) {
        return Err(format!(
            "material {i} ({}) has an empty shader program",
            m.name
        ));
    }
    for op in &m.shader {
        if let ShaderOp::Tex(s) = op {
            for t in std::iter::once(s.texture).chain(s.second.map(|x| x.texture)) {
                if t >= scene.textures.len() {
                    return Err(format!(
                        "material {i} ({}) samples texture {t} of {}",
                        m.name,
                        scene.textures.len()
                    ));
                }
            }
            if s.uv_set > 1 {
                return Err(format!(
                    "material {i} ({}) uses UV set {} (expected 0 or 1)",
                    m.name, s.uv_set
                ));
            }
        }
    }
    Ok(())
}

/// Mesh `i`: a material that exists, UVs for every position (second UVs
/// where the material samples them), whole triangles of vertices that
/// exist, draw calls covering every triangle.
fn validate_mesh(scene: &Scene, i: usize, m: &Mesh) -> Result<(), String> {
    let n = m.positions.len();
    if m.material >= scene.materials.len() {
        return Err(format!(
            "mesh {i} uses material {} of {}",
            m.material,
            scene.materials.len()
        ));
    }
    if m.uv.len() != n {
        return Err(format!("mesh {i}: {} UVs for {n} positions", m.uv.len()));
    }
    match &m.uv2 {
        Some(uv2) if uv2.len() != n => {
            return Err(format!(
                "mesh {i}: {} second UVs for {n} positions",
                uv2.len()
            ))
        }
        None => {
            let needs = scene.materials[m.material]
                .shader
                .iter()
                .any(|op| matches!(op, ShaderOp::Tex(s) if s.uv_set == 1));
            if needs {
                return Err(format!(
                    "mesh {i}: material {} samples UV set 1 but the mesh has no second UVs",
                    scene.materials[m.material].name
                ));
            }
        }
        _ => {}
    }
    if !m.indices.len().is_multiple_of(3) {
        return Err(format!(
            "mesh {i}: {} indices (expected a multiple of 3)",
            m.indices.len()
        ));
    }
    match &m.clip_w {
        Some(w) if !matches!(scene.camera, Camera::Clip) => {
            return Err(format!(
                "mesh {i}: {} clip-space w values, but the camera is not a clip-space one",
                w.len()
            ))
        }
        Some(w) if w.len() != n => {
            return Err(format!("mesh {i}: {} w values for {n} positions", w.len()))
        }
        _ => {}
    }
    if let Some(&bad) = m.indices.iter().find(|&&x| x as usize >= n) {
        return Err(format!("mesh {i}: index {bad} of {n} vertices"));
    }
    let drawn: u64 = m.draws.iter().map(|d| u64::from(d.triangles)).sum();
    if !m.draws.is_empty() && drawn != m.indices.len() as u64 / 3 {
        return Err(format!(
            "mesh {i}: its draw calls cover {drawn} triangles of {}",
            m.indices.len() / 3
        ));
    }
    Ok(())
}
