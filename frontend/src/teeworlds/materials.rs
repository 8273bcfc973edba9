//! Materials and textures: the fragment program of a 2D material (the
//! definition's shader template, or its ALU work alone when untextured),
//! and the map's images as textures (external `mapres/` PNGs or embedded
//! pixels).

use super::*;

/// The fragment program of a material: the definition's template (default
/// `sprite`) on `tex`, or, untextured, the template's ALU work alone.
pub(crate) fn program(
    template: Option<&str>,
    tex: Option<usize>,
    filter: Filter,
) -> Result<Vec<ShaderOp>, String> {
    let t = tex.unwrap_or(0);
    let full = match template.unwrap_or("sprite") {
        "sprite" => shader::sprite(t, filter),
        "unlit" => shader::unlit(t, filter),
        "standard" => shader::standard(t, filter),
        "lightmapped" => {
            return Err(
                "shader template `lightmapped` needs a lightmap; 2D scenes have none".into(),
            )
        }
        other => {
            return Err(format!(
                "unknown shader template `{other}` (known: {})",
                shader::TEMPLATES.join(", ")
            ))
        }
    };
    if tex.is_some() {
        return Ok(full);
    }
    let alu: u32 = full
        .iter()
        .map(|op| match op {
            ShaderOp::Alu(n) => *n,
            ShaderOp::Tex(_) => 0,
        })
        .sum();
    Ok(vec![ShaderOp::Alu(alu)])
}

fn load_png(path: &Path) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let bytes =
        std::fs::read(path).map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
    let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
        .map_err(|e| SceneError::in_file(path, format!("PNG: {e}")))?
        .to_rgba8();
    let (w, h) = img.dimensions();
    if w == 0 || h == 0 {
        return Err(SceneError::in_file(path, "PNG has no pixels"));
    }
    Ok((w, h, img.into_raw()))
}

pub(super) fn map_texture(
    data_root: &Path,
    map_path: &Path,
    df_bytes: &[u8],
    img: &MapImage,
) -> Result<Texture, SceneError> {
    if img.external {
        let path = data_root.join("mapres").join(format!("{}.png", img.name));
        let (width, height, rgba) = load_png(&path)?;
        return Ok(Texture {
            name: format!("mapres/{}.png", img.name),
            width,
            height,
            rgba,
            repeat: false,
        });
    }
    let df = Datafile::parse(map_path, df_bytes)?;
    let raw = df.data(img.data, img.offset + 20, "embedded image")?;
    let n = img.width as usize * img.height as usize;
    if raw.len() != n * img.channels as usize {
        return Err(SceneError::at(
            map_path,
            img.offset + 20,
            format!(
                "embedded image {:?}: {} bytes of pixels, {}x{}x{} expected",
                img.name,
                raw.len(),
                img.width,
                img.height,
                img.channels
            ),
        ));
    }
    let rgba = if img.channels == 4 {
        raw
    } else {
        raw.chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect()
    };
    Ok(Texture {
        name: format!("{} (embedded)", img.name),
        width: img.width,
        height: img.height,
        rgba,
        repeat: false,
    })
}
