//! Loading a scene from its definition: procedural scenes are built, game
//! scenes read from the scene cache ([`super::fetch`]) by their game's
//! loader.

use super::def::{Game, Route, SceneDef};
use super::fetch::{data_root, is_fetched, package_root};
use super::{procedural, Scene, SceneError};

/// Load the scene a definition names: procedural scenes directly, game
/// scenes from the cache through the game's loader.
pub fn load_scene(def: &SceneDef) -> Result<Scene, SceneError> {
    let game = def.game;
    if def.route == Route::Engine {
        return Err(SceneError::in_file(
            &def.name,
            format!(
                "route = \"engine\": the scene's draw calls come from the game's engine, not a \
                 loader; run `wasp scenes capture {}`, then import the capture with `wasp \
                 import-gl`",
                def.name
            ),
        ));
    }
    if game == Game::Procedural {
        return procedural::load(def);
    }
    if !is_fetched(game) {
        return Err(SceneError::in_file(
            package_root(game),
            format!(
                "scene {} needs the {} data: run `wasp scenes fetch {}` first",
                def.name,
                game.name(),
                game.name()
            ),
        ));
    }
    let root = data_root(game);
    match game {
        Game::Supertuxkart => super::supertuxkart::load(&root, def),
        Game::Openarena => super::openarena::load(&root, def),
        Game::Teeworlds => super::teeworlds::load(&root, def),
        Game::FrozenBubble => super::frozen_bubble::load(&root, def),
        Game::Procedural => procedural::load(def),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn procedural_scenes_load_without_data() {
        let def = SceneDef {
            name: "procedural-sprites".into(),
            ..crate::def::test_def(Game::Procedural, "sprites", "full", 128, 64)
        };
        assert_eq!(load_scene(&def).unwrap().name, "procedural:sprites");
    }

    #[test]
    fn the_repository_scene_files_parse() {
        let defs = super::super::def::all().unwrap();
        for name in ["procedural-plane", "procedural-sprites"] {
            let d = defs.iter().find(|d| d.name == name).expect(name);
            assert_eq!(d.game, Game::Procedural);
            assert!(load_scene(d).is_ok());
        }
    }
}
