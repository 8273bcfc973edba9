//! The text formats: the BSP's entity list and the `.shader` scripts
//! (the stages, blend functions and sky of each surface).

use super::*;

/// Tokens of Quake text (entities, shader scripts): `//` and `/* */`
/// comments, quoted strings, braces; each with its byte offset.
pub(super) fn tokenize(text: &str) -> Vec<(usize, String, bool)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_whitespace() {
            i += 1;
        } else if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if c == b'/' && b.get(i + 1) == Some(&b'*') {
            i += 2;
            while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b'/')) {
                i += 1;
            }
            i = (i + 2).min(b.len());
        } else if c == b'"' {
            let start = i;
            i += 1;
            let s = i;
            while i < b.len() && b[i] != b'"' {
                i += 1;
            }
            out.push((
                start,
                String::from_utf8_lossy(&b[s..i.min(b.len())]).into_owned(),
                true,
            ));
            i += 1;
        } else if c == b'{' || c == b'}' {
            out.push((i, (c as char).to_string(), false));
            i += 1;
        } else {
            let s = i;
            while i < b.len() && !b[i].is_ascii_whitespace() && b[i] != b'{' && b[i] != b'}' {
                if b[i] == b'/' && matches!(b.get(i + 1), Some(b'/' | b'*')) {
                    break;
                }
                i += 1;
            }
            out.push((s, String::from_utf8_lossy(&b[s..i]).into_owned(), false));
        }
    }
    out
}

/// Parse the entity lump: a list of key/value maps.
pub fn parse_entities(
    text: &str,
    file: &Path,
    base: usize,
) -> Result<Vec<HashMap<String, String>>, SceneError> {
    let toks = tokenize(text);
    let mut out = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let (at, t, quoted) = &toks[i];
        if *quoted || t != "{" {
            return Err(SceneError::at(
                file,
                (base + at) as u64,
                format!("entities: expected `{{`, found `{t}`"),
            ));
        }
        i += 1;
        let mut e = HashMap::new();
        loop {
            let Some((at, k, kq)) = toks.get(i) else {
                return Err(SceneError::at(
                    file,
                    (base + text.len()) as u64,
                    "entities: unterminated entity (missing `}`)",
                ));
            };
            if !kq && k == "}" {
                i += 1;
                break;
            }
            let Some((_, v, _)) = toks.get(i + 1) else {
                return Err(SceneError::at(
                    file,
                    (base + at) as u64,
                    format!("entities: key `{k}` without a value"),
                ));
            };
            e.insert(k.clone(), v.clone());
            i += 2;
        }
        out.push(e);
    }
    Ok(out)
}

/// One shader stage.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Stage {
    /// `map` / `clampMap` / first `animMap` image (`$lightmap`, `$whiteimage` kept as is).
    pub map: Option<String>,
    /// Set by `clampMap`.
    pub clamp: bool,
    /// `blendFunc` present (and not `GL_ONE GL_ZERO`).
    pub blend: bool,
    /// `alphaFunc` present.
    pub alpha_test: bool,
}

/// A shader script entry.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ShaderDef {
    /// Name.
    pub name: String,
    /// `surfaceparm` values (lower case).
    pub surfaceparms: Vec<String>,
    /// `skyParms` far box base name (`-` omitted).
    pub farbox: Option<String>,
    /// Stages in order.
    pub stages: Vec<Stage>,
    /// `nopicmip` or `nomipmaps`: the engine uploads the stages' images at
    /// their size whatever `r_picmip` is (see [`super::upload`]).
    pub nopicmip: bool,
}

impl ShaderDef {
    /// Whether a `surfaceparm` is set.
    pub fn has(&self, parm: &str) -> bool {
        self.surfaceparms.iter().any(|p| p == parm)
    }

    /// The first stage image that is not `$lightmap` / `$whiteimage`.
    pub fn base(&self) -> Option<(&str, bool)> {
        self.stages.iter().find_map(|s| {
            s.map
                .as_deref()
                .filter(|m| !m.starts_with('$'))
                .map(|m| (m, s.clamp))
        })
    }

    /// Whether a stage maps `$lightmap`.
    pub fn uses_lightmap(&self) -> bool {
        self.stages.iter().any(|s| {
            s.map
                .as_deref()
                .is_some_and(|m| m.eq_ignore_ascii_case("$lightmap"))
        })
    }

    /// The blend mode the stages imply.
    pub fn blend(&self) -> Blend {
        match self.stages.first() {
            Some(s) if s.blend => Blend::AlphaBlend,
            _ if self.stages.iter().any(|s| s.alpha_test) => Blend::AlphaTest,
            _ => Blend::Opaque,
        }
    }
}

/// Parse a shader script (`file` names it in errors).
pub fn parse_shaders(text: &str, file: &Path) -> Result<Vec<ShaderDef>, SceneError> {
    let toks = tokenize(text);
    let err = |at: usize, m: String| SceneError::at(file, at as u64, m);
    let mut out = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let (at, name, _) = &toks[i];
        if name == "{" || name == "}" {
            return Err(err(*at, format!("expected a shader name, found `{name}`")));
        }
        match toks.get(i + 1) {
            Some((_, b, false)) if b == "{" => {}
            _ => {
                return Err(err(
                    *at,
                    format!("shader `{name}`: expected `{{` after the name"),
                ))
            }
        }
        i += 2;
        let mut def = ShaderDef {
            name: name.clone(),
            ..Default::default()
        };
        let mut stage: Option<Stage> = None;
        loop {
            let Some((at, t, q)) = toks.get(i) else {
                return Err(err(text.len(), format!("shader `{name}`: missing `}}`")));
            };
            let lower = t.to_ascii_lowercase();
            let arg = |k: usize| toks.get(i + k).map(|t| t.1.clone()).unwrap_or_default();
            match (lower.as_str(), q) {
                ("{", false) => {
                    if stage.is_some() {
                        return Err(err(*at, format!("shader `{name}`: nested stage")));
                    }
                    stage = Some(Stage::default());
                }
                ("}", false) => match stage.take() {
                    Some(s) => def.stages.push(s),
                    None => {
                        i += 1;
                        break;
                    }
                },
                (keyword, _) => apply_keyword(&mut def, &mut stage, keyword, arg),
            }
            i += 1;
        }
        out.push(def);
    }
    Ok(out)
}

/// Apply one keyword of a shader (`keyword`, lower case; `arg(k)` its
/// k-th argument) to the shader `def` or, inside a stage, to `stage`:
/// `surfaceparm`, `skyParms`, `nopicmip` and `nomipmaps` outside stages; a
/// stage's first `map`, `clampMap` or `animMap` image, `blendFunc` and
/// `alphaFunc`. Other keywords are ignored.
fn apply_keyword(
    def: &mut ShaderDef,
    stage: &mut Option<Stage>,
    keyword: &str,
    arg: impl Fn(usize) -> String,
) {
    match keyword {
        "surfaceparm" if stage.is_none() => {
            def.surfaceparms.push(arg(1).to_ascii_lowercase());
        }
        "skyparms" if stage.is_none() => {
            let fb = arg(1);
            if fb != "-" && !fb.is_empty() {
                def.farbox = Some(fb);
            }
        }
        "nopicmip" | "nomipmaps" if stage.is_none() => def.nopicmip = true,
        "map" | "clampmap" => {
            if let Some(s) = stage.as_mut() {
                if s.map.is_none() {
                    s.map = Some(arg(1));
                    s.clamp = keyword == "clampmap";
                }
            }
        }
        "animmap" => {
            if let Some(s) = stage.as_mut() {
                if s.map.is_none() {
                    s.map = Some(arg(2));
                }
            }
        }
        "blendfunc" => {
            if let Some(s) = stage.as_mut() {
                let a = arg(1).to_ascii_lowercase();
                let b = arg(2).to_ascii_lowercase();
                s.blend = !(a == "gl_one" && b == "gl_zero");
            }
        }
        "alphafunc" => {
            if let Some(s) = stage.as_mut() {
                s.alpha_test = true;
            }
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_shader_scripts() {
        let text = r#"
// comment { not a brace
textures/a/lit
{
    qer_editorimage textures/a/x.tga
    surfaceparm nomarks
    {
        map $lightmap
        rgbGen identity
    }
    {
        map textures/a/base.tga
        blendFunc GL_DST_COLOR GL_ZERO
    }
}
textures/a/glass { surfaceparm trans /* c */ { map textures/a/glass.jpg blendfunc add } }
textures/a/grate
{
    { clampMap textures/a/grate.tga alphaFunc GE128 depthWrite }
    { map $lightmap blendFunc filter }
}
textures/a/sky { surfaceparm sky surfaceparm noimpact skyparms env/red - - }
textures/a/anim { { animMap 5 textures/a/f1.tga textures/a/f2.tga } }
textures/a/hud { nopicmip { map textures/a/h.tga } }
textures/a/flat { NoMipMaps { map textures/a/f.tga } }
"#;
        let s = parse_shaders(text, Path::new("x.shader")).unwrap();
        assert_eq!(s.len(), 7);
        assert!(s[5].nopicmip && s[6].nopicmip);
        assert!(s[..5].iter().all(|d| !d.nopicmip));
        assert_eq!(s[0].name, "textures/a/lit");
        assert_eq!(s[0].base(), Some(("textures/a/base.tga", false)));
        assert!(s[0].uses_lightmap());
        assert_eq!(s[0].blend(), Blend::Opaque);
        assert_eq!(s[1].blend(), Blend::AlphaBlend);
        assert_eq!(s[2].base(), Some(("textures/a/grate.tga", true)));
        assert_eq!(s[2].blend(), Blend::AlphaTest);
        assert!(s[3].has("sky") && s[3].base().is_none());
        assert_eq!(s[3].farbox.as_deref(), Some("env/red"));
        assert_eq!(s[4].base(), Some(("textures/a/f1.tga", false)));
        let e = parse_shaders("a { { map x }", Path::new("x.shader")).unwrap_err();
        assert!(e.message.contains("missing"), "{e}");
        let e = parse_shaders("a b { }", Path::new("x.shader")).unwrap_err();
        assert_eq!(e.offset, Some(0));
        let e = parse_entities("{ \"a\" \"b\" } x", Path::new("e"), 100).unwrap_err();
        assert_eq!(e.offset, Some(112));
    }
}
