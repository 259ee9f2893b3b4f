//! Blender's live link end to end: the add-on's "Live export on save" in a bpy session,
//! `rt watch --headless` on what it exports; each save is one reload of the right kind.
//! Needs RT_BPY_PYTHON, a Python with `bpy` (scripts/test sets one up).

use crate::watch_harness;

use watch_harness::{edit_and_expect_reload, watch_blender_session};

#[test]
fn each_save_in_blender_is_one_reload_in_rt_watch() {
    let (mut blender, mut watch, _) = watch_blender_session("live_watch.py", "blender-live-watch");
    let steps =
        [(1, "kind=asset cause=cube.gltf"), (2, "kind=camera cause=scene.toml"), (3, "kind=asset cause=cube.rtmesh")];
    for (step, expected) in steps {
        edit_and_expect_reload(&mut blender, &mut watch, step, expected);
    }
    blender.finish();
    assert!(!watch.log().iter().any(|l| l.starts_with("error ")), "{}", watch.log().join("\n"));
    watch.stop();
}
