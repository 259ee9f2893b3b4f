//! Shader node graphs evaluated on the GPU against Cycles (`tests/cycles/make_node_graph_refs.py`
//! renders the references and exports the scenes with `blender/rt_export.py`). The per-node
//! scenes are grids of tiles that only emit, each tile's colour the output of a small graph:
//! noise of every fractal type, distortion and colour, ramps, checkers; every Math operation
//! over −3…3 (division by zero, logs and roots of negatives, powers of negative bases
//! included); the Mix node's colour blends; gradients and Vector Math; Map Range, Clamp,
//! Invert, RGB to BW, Separate/Combine; and on smooth spheres the nodes that read the
//! normal and the view (Layer Weight, Fresnel, Geometry, Texture Coordinate). A pixel is the
//! graph's mean over the pixel, so rt and Cycles agree within the noise of sampling the
//! pixel's area — per colour channel and 8×8 block. `graph_material` is a whole procedural
//! Principled material lit by a uniform world.

use crate::common;

use common::layers::blocks;
use common::measured::{Measured, render_measured};
use common::reference::Noiseless;
use common::{reference, repo};

/// Samples per pixel of the committed references (`make_node_graph_refs.py --spp`).
const REFERENCE_SPP: f64 = 1024.0;
const SPP: u32 = 64;
const BLOCK: usize = 8;

/// rt's render of scene `name` with paths of `max_bounces` (Cycles' Max Bounces + 1: rt
/// counts the surface the camera sees), and Cycles' image.
fn load(name: &str, max_bounces: u32) -> (Measured, Vec<[f32; 3]>) {
    let dir = repo().join(format!("tests/cycles/scenes/{name}"));
    let scene = rt::scene::load(&dir.join("scene.toml")).unwrap_or_else(|e| panic!("{e}"));
    let (ours, _) = render_measured(scene, |r| (r.spp, r.max_bounces) = (SPP, max_bounces));
    let file = repo().join(format!("tests/cycles/{name}.exr"));
    let reference = image::open(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display())).into_rgb32f();
    (ours, reference.pixels().map(|p| p.0).collect())
}

/// Every 8×8 block's mean of every channel within 5 σ of Cycles' (σ from rt's measured
/// standard error of the channel, scaled by both renders' sample counts), with `floor`
/// for blocks without noise.
fn check_channels(name: &str, floor: f32) {
    // The tiles only emit: one bounce finds nothing more.
    check_channels_of(name, floor, 1);
}

/// `check_channels` of a scene lit by lamps, rendered with `max_bounces`.
fn check_channels_of(name: &str, floor: f32, max_bounces: u32) {
    let (ours, reference) = load(name, max_bounces);
    let (w, h) = (ours.image.width as usize, ours.image.height as usize);
    let noise_scale = (1.0 + SPP as f64 / REFERENCE_SPP).sqrt();
    let mut worst = (0.0f64, String::new());
    for ((bx, by), pixels) in blocks(w, h, BLOCK) {
        let (mut a, mut b, mut var) = ([0.0f64; 3], [0.0f64; 3], [0.0f64; 3]);
        for &i in &pixels {
            for c in 0..3 {
                a[c] += ours.image.pixels[i][c] as f64;
                b[c] += reference[i][c] as f64;
                var[c] += (ours.channel_error[i][c] as f64).powi(2);
            }
        }
        let n = (BLOCK * BLOCK) as f64;
        for c in 0..3 {
            let sigma = var[c].sqrt() / n * noise_scale;
            let bound = 5.0 * sigma + floor as f64 * (1.0 + (b[c] / n).abs());
            let ratio = (a[c] - b[c]).abs() / n / bound;
            if ratio > worst.0 {
                worst = (ratio, format!("block ({bx}, {by}) channel {c}: {:.5} vs Cycles {:.5}", a[c] / n, b[c] / n));
            }
        }
    }
    println!("{name:16} worst block at {:.2} of its bound: {}", worst.0, worst.1);
    assert!(worst.0 <= 1.0, "{name}: {} is {:.2} times its bound from Cycles'", worst.1, worst.0);
}

#[test]
fn noise_of_every_kind_ramps_and_checkers_match_cycles() {
    check_channels("graph_noise", 1e-3);
}

/// Blackbody across its fit's pieces and ends, Wavelength across the visible range and
/// past its ends, Vector Math's Power and Sign, and colours combined and separated in HSL.
#[test]
fn blackbody_wavelength_and_hsl_match_cycles() {
    check_channels("graph_spectrum", 1e-3);
}

/// Texture Coordinate's Camera, Window and Reflection on spheres seen in perspective
/// through a shifted lens.
#[test]
fn camera_window_and_reflection_coordinates_match_cycles() {
    check_channels("graph_camera", 1e-3);
}

/// Object Info: Random of differently named objects (non-ASCII names too, as Cycles hashes
/// their bytes), Object Color and Alpha, Location.
#[test]
fn object_info_matches_cycles() {
    check_channels("graph_object_info", 1e-3);
}

/// Noise of 1, 2 and 4 dimensions: every fractal type, distortion, colour, W linked and
/// constant (1D reads W only, 2D the vector's x and y).
#[test]
fn noise_of_one_two_and_four_dimensions_matches_cycles() {
    check_channels("graph_noise_dimensions", 1e-3);
}

/// Bump nodes under a low sun: heights of noise on Object, Generated and Camera coordinates,
/// a wave on the UVs, the Position's sine, Magic and Voronoi; inverted, at half strength,
/// chained, into a Diffuse BSDF, under a metal, read by Layer Weight, on a turned and
/// stretched tile and on smooth spheres, in perspective.
#[test]
fn bump_nodes_match_cycles() {
    // Cycles' one bounce: light that neighbours throw at each other.
    check_channels_of("graph_bump", 1e-3, 2);
}

/// Geometry's Tangent: the radial tangent about each object's Z axis through its Generated
/// coordinates, as Cycles' `primitive_tangent`, on turned and stretched spheres; crossed with
/// the normal and against the view.
#[test]
fn geometry_tangent_matches_cycles() {
    check_channels("graph_tangent", 1e-3);
}

/// Object Info's Material Index: the Pass Index of each tile's material (0 to 7, one shared by
/// two tiles), as a value and through a ramp; the exporter writes it as a constant.
#[test]
fn material_index_matches_cycles() {
    check_channels("graph_material_index", 1e-3);
}

#[test]
fn every_math_operation_matches_cycles() {
    check_channels("graph_math", 1e-3);
}

#[test]
fn the_mix_nodes_colour_blends_match_cycles() {
    check_channels("graph_color", 1e-3);
}

#[test]
fn gradients_and_vector_math_match_cycles() {
    check_channels("graph_vector", 1e-3);
}

#[test]
fn voronoi_of_every_feature_and_metric_matches_cycles() {
    check_channels("graph_voronoi", 1e-3);
}

/// Voronoi of 1, 2 and 4 dimensions: each feature, metrics, fractal octaves, W read (1D and
/// 4D) and W written (a 1D point's position, a 4D point's fourth component), Position.
#[test]
fn voronoi_of_one_two_and_four_dimensions_matches_cycles() {
    check_channels("graph_voronoi_dimensions", 1e-3);
}

/// Emission strengths a graph drives, on Emission shaders and a black Principled's
/// emission, alone and with a driven colour (their product).
#[test]
fn driven_emission_strengths_match_cycles() {
    check_channels("graph_emission_strength", 1e-3);
}

/// Camera Data's View Vector, View Z Depth and View Distance, in perspective through a
/// shifted lens.
#[test]
fn camera_data_matches_cycles() {
    check_channels("graph_camera_data", 1e-3);
}

/// Vector Transform of points, vectors and normals between world, object and camera space,
/// on spheres turned and stretched (normals by the inverse transposes).
#[test]
fn vector_transforms_match_cycles() {
    check_channels("graph_vector_transform", 1e-3);
}

/// The Normal node: its direction normalised, and its Dot with a normal, a point and the
/// incoming direction (each normalised first, as Cycles does).
#[test]
fn the_normal_node_matches_cycles() {
    check_channels("graph_normal_node", 1e-3);
}

/// Attribute and Color Attribute of every kind Cycles reads (`make_attribute_refs.py`):
/// byte and float colours on points and corners, a value, a vector, an integer on faces, a
/// boolean, the uv map, the mesh's default colour, names the mesh lacks, an attribute as a
/// texture's coordinates.
#[test]
fn attributes_match_cycles() {
    check_channels("graph_attributes", 1e-3);
}

/// Geometry's Random Per Island (Cycles' hash of each island's root vertex, which the
/// exporter computes per face): two meshes of eight islands, plain and through a ramp.
#[test]
fn random_per_island_matches_cycles() {
    check_channels("graph_random_per_island", 1e-3);
}

/// Geometry's Parametric ((1 − u − v, u, 0) over each triangle, which the exporter writes as
/// corner values): itself, through a ramp, and the distance to a triangle's edges.
#[test]
fn parametric_matches_cycles() {
    check_channels("graph_parametric", 1e-3);
}

/// Geometry's Pointiness (computed per vertex by the exporter as Cycles does, duplicates
/// welded) of six solids, plain and through a ramp, and of a cube of unconnected faces.
#[test]
fn pointiness_matches_cycles() {
    check_channels("graph_pointiness", 1e-3);
}

/// A Bump of a point attribute, alone and plus a noise, on spheres under a low sun: the
/// attribute read a step away along the surface, as Cycles' `svm_node_attr_bump_dx`.
#[test]
fn a_bump_of_an_attribute_matches_cycles() {
    check_channels_of("graph_attributes_bump", 1e-3, 3);
}

/// A World whose Background is a node graph (`make_world_refs.py`): a sky gradient with
/// noise clouds lighting spheres and a floor, the camera seeing another colour (Light
/// Path's Is Camera Ray); and the same gradient beside a sun lamp.
#[test]
fn world_graphs_match_cycles() {
    check_channels_of("graph_world", 1e-3, 5);
    check_channels_of("graph_world_sun", 1e-3, 5);
}

/// A World of Texture Coordinate's Window and Camera (`make_world_refs.py`), seen directly
/// and in a metal sphere through a turned and rolled camera: the direction placed at the
/// camera, as Cycles does for the World.
#[test]
fn a_world_of_window_and_camera_coordinates_matches_cycles() {
    check_channels_of("graph_world_camera", 1e-3, 5);
    // Through an orthographic camera: Window at a camera ray's origin, at the direction
    // itself as a point for the reflections.
    check_channels_of("graph_world_ortho", 1e-3, 5);
}

/// The same World through panoramic cameras (equirectangular of a partial range with a
/// shifted lens, equisolid and equidistant fisheyes, a mirror ball), a floor of Window
/// beside it: Window is where the direction to a point (or the World's direction) falls on
/// the panorama's image, Camera is in the panoramic camera's space, as Cycles maps them.
#[test]
fn window_and_camera_coordinates_of_panoramic_cameras_match_cycles() {
    for name in
        ["graph_world_equirect", "graph_world_fisheye", "graph_world_fisheye_equidistant", "graph_world_mirror_ball"]
    {
        check_channels_of(name, 1e-3, 5);
    }
}

/// Mix Shaders of an emitting shader and a BSDF by a noise's or a gradient's factor
/// (`make_emitting_mix_refs.py`), the emitting one first or second, lighting a floor and
/// each other: light samples weigh the emission by the first shader's share.
#[test]
fn mix_shaders_of_emitting_shaders_match_cycles() {
    check_channels_of("graph_mix_emission", 1e-3, 5);
}

#[test]
fn waves_of_every_kind_match_cycles() {
    check_channels("graph_wave", 1e-3);
}

#[test]
fn magic_of_every_depth_matches_cycles() {
    check_channels("graph_magic", 1e-3);
}

#[test]
fn bricks_of_every_setting_match_cycles() {
    check_channels("graph_brick", 1e-3);
}

/// White Noise of one to four dimensions over cells (constant per cell, so a pixel's mean
/// shows the hash itself).
#[test]
fn white_noise_of_every_dimension_matches_cycles() {
    check_channels("graph_white_noise", 1e-3);
}

/// Map Range of vectors: every interpolation, clamped or not, reversed ranges, steps per
/// component (none among them), components whose range is empty, read as a value.
#[test]
fn map_range_of_vectors_matches_cycles() {
    check_channels("graph_map_range", 1e-3);
}

#[test]
fn map_range_clamp_and_converters_match_cycles() {
    check_channels("graph_convert", 1e-3);
}

#[test]
fn nodes_that_read_the_normal_and_the_view_match_cycles() {
    check_channels("graph_shading", 1e-3);
}

/// `tests/cycles/scenes/NAME/` at 64×64, 256 spp and `max_bounces` against Cycles' image,
/// every block and channel within its noise.
fn check_scene(name: &str, max_bounces: u32) {
    let scene = rt::scene::load(&repo().join(format!("tests/cycles/scenes/{name}/scene.toml"))).unwrap();
    let (ours, _) = render_measured(scene, |r| (r.width, r.height, r.spp, r.max_bounces) = (64, 64, 256, max_bounces));
    let reference = repo().join(format!("tests/cycles/{name}.exr"));
    reference::compare_measured(&ours, &reference, REFERENCE_SPP, Noiseless::Absolute(1e-4)).check(name, "Cycles");
}

/// A Mix Shader whose factor is a graph (Layer Weight on a sphere, noise on the floor):
/// each shading point is one of its two shaders, picked by the factor.
#[test]
fn mix_shaders_by_a_graph_match_cycles() {
    check_scene("graph_mix", 9);
}

/// Mix Shaders of a constant factor of shaders no one parameter set holds (a diffuse and a
/// glossy, two Principled BSDFs, a glass and a diffuse): each shading point one of the two,
/// picked by the factor, as the graph-driven ones. Before, rt rendered the heavier shader
/// alone, with a warning.
#[test]
fn mix_shaders_of_a_constant_factor_match_cycles() {
    check_scene("graph_mix_constant", 9);
}

/// Light Path tricks: an emitter red to the camera and green to everything else (light
/// samples and bounces alike), a floor coloured by Is Diffuse Ray, a metal by Ray Length.
#[test]
fn light_path_tricks_match_cycles() {
    check_scene("graph_light_path", 7);
}

/// Light Path's Diffuse, Glossy and Transmission Depth, each a colour: a floor by its
/// diffuse bounces, two mirror balls facing each other by their glossy ones (each
/// reflection in the other one more), a glass ball by its transmissions.
#[test]
fn light_path_depths_of_each_kind_match_cycles() {
    check_scene("graph_light_path_depths", 7);
}

#[test]
fn a_procedural_principled_material_matches_cycles() {
    check_scene("graph_material", 9);
}

/// A scene's node shapes run as specialised code, and the interpreter (which runs scenes
/// with too many shapes) gives the same image: the same operations on the same values.
#[test]
fn specialised_and_interpreted_programs_give_the_same_image() {
    let scene = || rt::scene::load(&repo().join("tests/cycles/scenes/graph_math/scene.toml")).unwrap();
    let adjust = |r: &mut rt::render::RenderRequest| (r.width, r.height, r.spp, r.max_bounces) = (64, 64, 2, 1);
    let (specialised, features) = common::render_request(scene(), adjust);
    assert_ne!(features.node_code, 0, "graph_math's programs are specialised");
    let (interpreted, _) = common::render_request(scene(), |r| {
        adjust(r);
        r.features = Some(rt::scene::FeatureSet { node_code: 0, ..features });
    });
    let mut worst = 0.0f32;
    for (a, b) in specialised.pixels.iter().zip(&interpreted.pixels) {
        for c in 0..3 {
            worst = worst.max((a[c] - b[c]).abs() / (1.0 + b[c].abs()));
        }
    }
    println!("specialised vs interpreted: largest difference {worst:.2e}");
    assert!(worst <= 1e-4, "the specialised code differs from the interpreter's by {worst}");
}

/// Editing graphs in a live session (`rt watch`, Blender's viewport): a graph of another
/// shape builds its pipeline, and the session keeps only the code and pipelines of the
/// shapes it renders, however many edits come (before, each new shape's code and
/// pipeline stayed for the session's life).
#[test]
fn a_live_session_keeps_only_the_node_code_it_renders() {
    use rt::bvh::{BuildQuality, SceneGeometry};
    use rt::render::{GeometryUpdate, RenderRequest, SceneUpdate, Session};
    let load = |name: &str| rt::scene::load(&repo().join(format!("tests/cycles/scenes/{name}/scene.toml"))).unwrap();
    let render = |session: &mut Session| {
        let mut request = RenderRequest::from_scene(session.scene());
        (request.width, request.height, request.spp, request.max_bounces) = (16, 16, 1, 1);
        session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    };
    let mut session = Session::open(common::gpu(), load("graph_mix"), BuildQuality::Medium).unwrap();
    render(&mut session);
    let (_, built) = session.pipeline_cache().sizes();
    for name in ["graph_light_path", "graph_mix", "graph_light_path"] {
        let scene = load(name);
        let geometry = SceneGeometry::build(&scene, BuildQuality::Medium).unwrap();
        let update = SceneUpdate { scene, geometry: Some(GeometryUpdate::Replace(geometry)), shaders: None };
        session.apply(update).unwrap_or_else(|e| panic!("{e:#}"));
        render(&mut session);
        assert_ne!(session.features().node_code, 0, "{name} is specialised");
        assert_eq!(session.pipeline_cache().sizes(), (1, built), "after {name}: one code, as many pipelines");
    }
}

/// Cel shading with the Toon BSDF, an rt lobe module: a Toon Diffuse of noise colours under a
/// Toon Glossy rim mixed by Layer Weight per shading point, a Toon Diffuse and a Diffuse BSDF
/// mixed by a constant, a soft-edged Toon Diffuse of noise colours, under a low sun.
#[test]
fn toon_shading_matches_cycles() {
    check_scene("graph_toon", 7);
}

/// Shaders inside node groups: a metal group whose colour a noise outside drives through its
/// input, a Diffuse and a Glossy mixed by Layer Weight inside a group, a group inside a group
/// (checker colours made inside, the roughness passed through both), a floor of a group left at
/// its input's default.
#[test]
fn shaders_inside_node_groups_match_cycles() {
    check_scene("graph_node_groups", 7);
}

/// Object Info's Object Index: Blender's Pass Index of twelve tiles sharing one material (as a
/// value and, by its parity, through a ramp), and of a collection's tile instanced four times
/// (the instanced object's, as Cycles reads it, from the instance file).
#[test]
fn object_index_matches_cycles() {
    check_channels("graph_object_index", 1e-3);
}

/// Add Shaders of two BSDFs (a Diffuse and a Glossy, a Toon Diffuse and a Toon Glossy, a
/// Principled and a Sheen, a floor of a Diffuse and a rough Glossy) under a sun: each shading
/// point is one of the two at weight 2, as Cycles adds the closures.
#[test]
fn add_shaders_of_two_bsdfs_match_cycles() {
    check_scene("graph_add_shader", 7);
}

/// Attribute nodes of the View Layer type, folded to constants at export as Cycles folds
/// them: the view layer's custom properties, then the scene's, then the World's, or an RNA
/// path; a number, a boolean, arrays of three and four, a string (none), a missing name.
#[test]
fn view_layer_attributes_match_cycles() {
    check_channels("graph_view_layer_attributes", 1e-3);
}
