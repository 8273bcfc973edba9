//! The scene definitions shipped in `scenes/`, embedded in the binary so
//! that it works wherever it is installed (`cargo install`, a copied
//! binary). A folder named by `--scenes-dir` or `WASP_SCENES_DIR` adds
//! definitions or replaces these by name ([`super::def::all`]).

/// (name, TOML text) of every shipped scene, sorted by name.
pub const BUILTIN: &[(&str, &str)] = &[
    ("fb-level1", include_str!("../../scenes/fb-level1.toml")),
    (
        "fb-level100-wide",
        include_str!("../../scenes/fb-level100-wide.toml"),
    ),
    ("fb-level50", include_str!("../../scenes/fb-level50.toml")),
    (
        "oa-dm1-spawn0",
        include_str!("../../scenes/oa-dm1-spawn0.toml"),
    ),
    (
        "oa-dm1-spawn0-engine",
        include_str!("../../scenes/oa-dm1-spawn0-engine.toml"),
    ),
    (
        "oa-dm5-spawn1",
        include_str!("../../scenes/oa-dm5-spawn1.toml"),
    ),
    (
        "oa-dm5-spawn1-engine",
        include_str!("../../scenes/oa-dm5-spawn1-engine.toml"),
    ),
    (
        "oa-wrackdm17-spawn2",
        include_str!("../../scenes/oa-wrackdm17-spawn2.toml"),
    ),
    (
        "oa-wrackdm17-spawn2-engine",
        include_str!("../../scenes/oa-wrackdm17-spawn2-engine.toml"),
    ),
    (
        "procedural-plane",
        include_str!("../../scenes/procedural-plane.toml"),
    ),
    (
        "procedural-plane-lit",
        include_str!("../../scenes/procedural-plane-lit.toml"),
    ),
    (
        "procedural-sprites",
        include_str!("../../scenes/procedural-sprites.toml"),
    ),
    (
        "stk-blackforest-start",
        include_str!("../../scenes/stk-blackforest-start.toml"),
    ),
    (
        "stk-cocoatemple-start",
        include_str!("../../scenes/stk-cocoatemple-start.toml"),
    ),
    (
        "stk-lighthouse-start",
        include_str!("../../scenes/stk-lighthouse-start.toml"),
    ),
    (
        "stk-zengarden-driveline",
        include_str!("../../scenes/stk-zengarden-driveline.toml"),
    ),
    (
        "tw-dm1-spawn0",
        include_str!("../../scenes/tw-dm1-spawn0.toml"),
    ),
    (
        "tw-dm1-spawn0-engine",
        include_str!("../../scenes/tw-dm1-spawn0-engine.toml"),
    ),
    (
        "tw-dm6-center",
        include_str!("../../scenes/tw-dm6-center.toml"),
    ),
    (
        "tw-dm8-center",
        include_str!("../../scenes/tw-dm8-center.toml"),
    ),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::def::{list, SceneDef};
    use std::path::{Path, PathBuf};

    #[test]
    fn every_file_of_the_scenes_folder_is_embedded_as_is() {
        let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes"));
        let on_disk = list(&dir).unwrap();
        let names: Vec<&str> = BUILTIN.iter().map(|(n, _)| *n).collect();
        let disk: Vec<&str> = on_disk.iter().map(|d| d.name.as_str()).collect();
        assert_eq!(
            names, disk,
            "scenes/ and BUILTIN differ: add the file to BUILTIN"
        );
        for (name, text) in BUILTIN {
            let d = SceneDef::parse(text, Path::new(name)).unwrap();
            assert_eq!(&d.name, name, "the file stem is the scene's name");
            let file = std::fs::read_to_string(dir.join(format!("{name}.toml"))).unwrap();
            assert_eq!(*text, file);
        }
    }
}
