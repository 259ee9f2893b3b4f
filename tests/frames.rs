//! `rt render --frames A..B`: each frame's scene (#### in its name) rendered to its own
//! image, the same as rendering that scene alone, with one GPU start for all.

use crate::common;

use common::bounded::rt;
use common::{empty_temp_dir, repo};
use std::time::Duration;

#[test]
fn each_frame_is_the_render_of_its_own_scene() {
    let dir = empty_temp_dir("frames");
    let furnace = std::fs::read_to_string(repo().join("scenes/furnace.toml")).expect("furnace.toml");
    for frame in 1..=3 {
        let moved = furnace.replace("position = [0.0, 0.0, 3.0]", &format!("position = [0.{frame}, 0.0, 3.0]"));
        assert_ne!(moved, furnace, "the camera moves");
        std::fs::write(dir.join(format!("shot_{frame:04}.toml")), moved).expect("write a frame");
    }
    let size = ["--spp", "3", "--size", "16x12", "--progress", "none"];
    let run = |args: &[&str]| rt(&dir, &[args, &size[..]].concat(), Duration::from_secs(300));
    run(&["render", "shot_####.toml", "--frames", "1..3", "-o", "out_##.png"]).expect("frames", 0);
    for frame in 1..=3 {
        let alone = format!("alone_{frame}.png");
        run(&["render", &format!("shot_{frame:04}.toml"), "-o", &alone]).expect("alone", 0);
        let read = |name: &str| std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(read(&format!("out_{frame:02}.png")) == read(&alone), "frame {frame} is its scene's render");
    }
    run(&["render", "shot_####.toml", "--frames", "2..5", "-o", "x_####.png"])
        .expect("a missing frame", 1)
        .says("a missing frame", &["shot_0004.toml: no such scene file"]);
    assert!(!dir.join("x_0002.png").exists(), "nothing is rendered when a frame's scene is missing");
    run(&["render", "shot_0001.toml", "--frames", "1..2", "-o", "x.png"])
        .expect("no ####", 1)
        .says("no ####", &["needs #### where the frame number goes"]);
}
