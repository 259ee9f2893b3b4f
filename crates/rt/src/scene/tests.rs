use super::*;
use super::{AreaShape, LightShape};
use glam::{Mat4, Vec3};
use std::path::Path;

fn parse_ok(text: &str) -> Scene {
    parse(text, "scene.toml", Path::new("/scenes")).unwrap_or_else(|e| panic!("{e}"))
}

/// The full error text, `scene.toml:line:column: message`.
fn error(text: &str) -> String {
    match parse(text, "scene.toml", Path::new("/scenes")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

const EXAMPLE: &str = r#"
[render]
width = 320
height = 200
spp = 64
max_bounces = 8
exposure = -1.5

[camera]
position = [0.0, 1.5, 6.0]
look_at  = [0.0, 1.0, 0.0]
fov_y_deg = 40.0

[sky]
kind = "atmosphere"
[sun]
elevation_deg = 12.0
azimuth_deg = 140.0
radiance = [1.0, 2.0, 3.0]

[materials.mirror]
reflection = 1.0
hardness = 50

[materials.blue_glass]
base_color = [1.0, 1.0, 1.0]
diffuse = 0.0
transmission = 1.0
ior = 1.3
roughness = 0.03
emission = [0.01, 0.03, 0.05]
absorption = [0.02, 0.02, 0.015]
volume_emission = [0.0, 0.0, 0.0]

[[mesh]]
asset = "../assets/dragon"
material = "blue_glass"
rotate_deg = [-90.0, 0.0, 0.0]
translate = [-4.0, 0.0, -6.0]
scale = 1.0

[[sphere]]
center = [3.0, 1.0, 0.0]
radius = 1.0
material = "mirror"
"#;

#[test]
fn full_example_parses() {
    let s = parse_ok(EXAMPLE);
    assert_eq!(s.origin, "scene.toml");
    let render =
        RenderSettings { width: 320, height: 200, spp: 64, max_bounces: 8, exposure: -1.5, ..Default::default() };
    assert_eq!(s.render, render);
    let camera = Camera { position: Vec3::new(0.0, 1.5, 6.0), look_at: Vec3::Y, ..Camera::default() };
    assert_eq!(s.camera, camera);
    assert_eq!(s.sky, Sky::Atmosphere(Atmosphere::default()));
    let radiance = Some(Vec3::new(1.0, 2.0, 3.0));
    let sun = Sun { elevation_deg: 12.0, azimuth_deg: 140.0, angular_diameter_deg: 0.53, radiance };
    assert_eq!(s.sun, Some(sun));
    // File order, which is not alphabetical order here.
    let names: Vec<&str> = s.materials.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["mirror", "blue_glass"]);
    let glass = &s.materials[1].1;
    assert_eq!((glass.diffuse, glass.transmission, glass.ior), (0.0, 1.0, 1.3));
    assert_eq!(glass.absorption, [0.02, 0.02, 0.015]);
    let mirror = &s.materials[0].1;
    assert_eq!((mirror.reflection, mirror.hardness, mirror.diffuse), (1.0, Some(50.0), 1.0));
    assert_eq!(s.meshes.len(), 1);
    let mesh = &s.meshes[0];
    assert_eq!(mesh.asset, Path::new("/scenes/../assets/dragon"));
    assert_eq!(mesh.material.as_deref(), Some("blue_glass"));
    // -90° about X takes +Y to -Z, then the translation applies.
    let p = mesh.object_to_world.transform_point3(Vec3::Y);
    assert!(p.abs_diff_eq(Vec3::new(-4.0, 0.0, -7.0), 1e-6), "{p}");
    let sphere = Sphere { center: Vec3::new(3.0, 1.0, 0.0), radius: 1.0, material: Some("mirror".into()) };
    assert_eq!(s.spheres, [sphere]);
}

#[test]
fn atmosphere_keys_parse() {
    let s = parse_ok(
        "[sky]\nkind = \"atmosphere\"\nturbidity = 2.5\nrayleigh_scale = 0.5\nmie_g = 0.7\nmie_absorption = false\n\
         ozone = false\nground_albedo = [0.1, 0.2, 0.3]\nground_altitude_m = 1500\nmultiple_scattering = false\n\
         steps = 12\ntransmittance_lut = [128, 32]\nmultiple_scattering_lut = [16, 8]\n",
    );
    let expected = Atmosphere {
        turbidity: 2.5,
        rayleigh_scale: 0.5,
        mie_g: 0.7,
        mie_absorption: false,
        ozone: false,
        ground_albedo: Vec3::new(0.1, 0.2, 0.3),
        ground_altitude_m: 1500.0,
        multiple_scattering: false,
        steps: 12,
        transmittance_lut: [128, 32],
        multiple_scattering_lut: [16, 8],
    };
    assert_eq!(s.sky, Sky::Atmosphere(expected));
    let grey = parse_ok("[sky]\nkind = \"atmosphere\"\nground_albedo = 0.5\n");
    let Sky::Atmosphere(a) = grey.sky else { panic!("not an atmosphere") };
    assert_eq!(a.ground_albedo, Vec3::splat(0.5));
}

#[test]
fn empty_file_gives_defaults() {
    let s = parse_ok("");
    assert_eq!(s.render, RenderSettings::default());
    let camera = Camera::default();
    assert_eq!(s.camera, camera);
    assert_eq!((s.sky, s.sun), (Sky::Black, None));
    assert_eq!(parse_ok("[sky]\nkind = \"uniform\"\n").sky, Sky::Uniform { color: Vec3::ONE, sample_as_light: false });
}

/// One case a line: the scene with `|` between its lines, ` => `, then the
/// error after `scene.toml:`.
fn assert_errors(cases: &str) {
    for case in cases.lines().map(str::trim).filter(|c| !c.is_empty()) {
        let (text, expected) = case.split_once(" => ").expect("a case has ` => `");
        let text = text.split('|').map(str::trim).collect::<Vec<_>>().join("\n");
        assert_eq!(error(&text), format!("scene.toml:{expected}"), "{text}");
    }
}

#[test]
fn negative_radius_is_located() {
    assert_errors(
        r#"
        [[sphere]] | center = [0.0, 0.0, 0.0] | radius = 1.0 | | [materials.a] | | | | | | [[sphere]] | radius = -1 | center = [1, 2, 3] => 12:10: sphere 2: radius must be positive and at most 1e15 m (rt intersects spheres in f32), got -1
        [[sphere]] | center = [0.0, 0.0, 0.0] | radius = 1e20 => 3:10: sphere 1: radius must be positive and at most 1e15 m (rt intersects spheres in f32), got 1e20
        [[sphere]] | center = [0.0, -3e16, 0.0] | radius = 1.0 => 2:10: sphere 1: center must be within ±1e15 m (rt intersects spheres in f32), got -3e16
    "#,
    );
}

#[test]
fn unknown_keys_suggest_in_every_table() {
    assert_errors(
        r#"
        [render] | widht = 1 => 2:1: unknown key `widht` in [render]; did you mean `width`?
        [camera] | fov_deg = 1 => 2:1: unknown key `fov_deg` in [camera]; did you mean `fov_y_deg`?
        [sky] | kind = "uniform" | colr = [1, 1, 1] => 3:1: unknown key `colr` in [sky]; did you mean `color`?
        [sun] | elevation = 1 => 2:1: unknown key `elevation` in [sun]; did you mean `elevation_deg`?
        [materials.m] | | rougness = 0.5 => 3:1: unknown key `rougness` in [materials.m]; did you mean `roughness`?
        [materials.m] | sheen_tnt = [1, 1, 1] => 2:1: unknown key `sheen_tnt` in [materials.m]; did you mean `sheen_tint`?
        [materials.m] | diffuse_roughnes = 0.5 => 2:1: unknown key `diffuse_roughnes` in [materials.m]; did you mean `diffuse_roughness`?
        [materials.m] | thin_film_thicknes = 300 => 2:1: unknown key `thin_film_thicknes` in [materials.m]; did you mean `thin_film_thickness`?
        [materials.m] | specular_ior_levl = 0.5 => 2:1: unknown key `specular_ior_levl` in [materials.m]; did you mean `specular_ior_level`?
        [render] | microfacets = "single" => 2:1: unknown key `microfacets` in [render]; did you mean `microfacet`?
        [[mesh]] | asset = "a" | [[mesh]] | asset = "b" | materal = "m" => 5:1: unknown key `materal` in mesh 2; did you mean `material`?
        [[sphere]] | radious = 1 => 2:1: unknown key `radious` in sphere 1; did you mean `radius`?
        | meshes = [] => 2:1: unknown key `meshes` in the top-level table; did you mean `mesh`?
        [sky] | kind = "uniform" | hue = 1 => 3:1: unknown key `hue` in [sky]; expected one of `kind`, `color`, `sample_as_light`, `turbidity`, `rayleigh_scale`, `mie_g`, `mie_absorption`, `ozone`, `ground_albedo`, `ground_altitude_m`, `multiple_scattering`, `steps`, `transmittance_lut`, `multiple_scattering_lut`, `image`, `strength`, `rotation_deg`, `importance_sampling`, `color_space`, `graph`
        [sky] | kind = "atmosphere" | turbidty = 2 => 3:1: unknown key `turbidty` in [sky]; did you mean `turbidity`?
        [sky] | kind = "atmosphere" | ground_albeda = 0.2 => 3:1: unknown key `ground_albeda` in [sky]; did you mean `ground_albedo`?
        sky = { kind = "black", colour = [1, 1, 1] } => 1:25: unknown key `colour` in [sky]; did you mean `color`?
        [sky] | kind = "atmosfere" => 2:8: [sky]: unknown kind `atmosfere`; did you mean `atmosphere`?
        [sky] | kind = "grey" => 2:8: [sky]: unknown kind `grey`; expected one of `black`, `uniform`, `atmosphere`, `environment`, `graph`
        [materials.m] | tangent = "radial_w" => 2:11: [materials.m]: unknown tangent `radial_w`; did you mean `radial_z`?
    "#,
    );
}

#[test]
fn undefined_material_suggests() {
    assert_errors(
        r#"
        [materials.mirror] | [materials.glass] | [[sphere]] | center = [0, 0, 0] | radius = 1 | material = "mirorr" => 6:12: sphere 1: material `mirorr` names no [materials.*] table; did you mean `mirror`?
        [[mesh]] | asset = "a" | material = "gold" => 3:12: mesh 1: material `gold` names no [materials.*] table
    "#,
    );
}

#[test]
fn non_finite_numbers_are_rejected() {
    assert_errors(
        r#"
        [camera] | fov_y_deg = nan => 2:13: [camera]: fov_y_deg must be finite, got NaN
        [render] | exposure = -inf => 2:12: [render]: exposure must be finite, got -inf
        [[sphere]] | center = [0, nan, 0] | radius = 1 => 2:10: sphere 1: center must be finite, got NaN
        [[mesh]] | asset = "a" | translate = [inf, 0, 0] => 3:13: mesh 1: translate must be finite, got inf
        [materials.m] | ior = nan => 2:7: [materials.m]: ior must be finite, got NaN
    "#,
    );
}

#[test]
fn out_of_range_values_are_located() {
    assert_errors(
        r#"
        [render] | width = 0 => 2:9: [render]: width must be in 1..=16384, got 0
        [render] | height = 16385 => 2:10: [render]: height must be in 1..=16384, got 16385
        [render] | spp = 0 => 2:7: [render]: spp must be at least 1, got 0
        [camera] | fov_y_deg = 180 => 2:13: [camera]: fov_y_deg must be in (0, 180), got 180
        [camera] | position = [0, 1, 0] => 1:1: [camera]: look_at must differ from position
        [sky] | kind = "black" | color = [1, 1, 1] => 3:9: [sky]: color only applies to kind = "uniform"
        [sky] | kind = "uniform" | turbidity = 2 => 3:13: [sky]: turbidity only applies to kind = "atmosphere"
        [sky] | kind = "atmosphere" | turbidity = -1 => 3:13: [sky]: turbidity must be in [0, 100], got -1
        [sky] | kind = "atmosphere" | rayleigh_scale = nan => 3:18: [sky]: rayleigh_scale must be finite, got NaN
        [sky] | kind = "atmosphere" | mie_g = 1 => 3:9: [sky]: mie_g must be in (-1, 1), got 1
        [sky] | kind = "atmosphere" | ground_albedo = [0.2, 1.5, 0.2] => 3:17: [sky]: ground_albedo must be in [0, 1], got 1.5
        [sky] | kind = "atmosphere" | ground_altitude_m = -5 => 3:21: [sky]: ground_altitude_m must be in [0, 1000000], got -5
        [sky] | kind = "atmosphere" | steps = 1 => 3:9: [sky]: steps must be in 2..=256, got 1
        [sky] | kind = "atmosphere" | transmittance_lut = [256, 2] => 3:21: [sky]: transmittance_lut entries must be in 4..=1024, got 2
        [sky] | kind = "atmosphere" | multiple_scattering_lut = [512, 32] => 3:27: [sky]: multiple_scattering_lut entries must be in 4..=256, got 512
        [sky] | kind = "uniform" | color = [1, -1, 1] => 3:9: [sky]: color must be non-negative, got -1
        [sun] | elevation_deg = 91 | azimuth_deg = 0 => 2:17: [sun]: elevation_deg must be in [-90, 90], got 91
        [sun] | elevation_deg = 1 | azimuth_deg = 0 | angular_diameter_deg = 0 => 4:24: [sun]: angular_diameter_deg must be in (0, 90), got 0
        [materials.m] | base_color = [1, 0.5, -0.2] => 2:14: [materials.m]: base_color must be non-negative, got -0.2
        [materials.m] | transmission = -1 => 2:16: [materials.m]: transmission must be non-negative, got -1
        [materials.m] | ior = 0.9 => 2:7: [materials.m]: ior must be at least 1, got 0.9
        [materials.m] | roughness = 1.5 => 2:13: [materials.m]: roughness must be in [0, 1], got 1.5
        [materials.m] | hardness = 0 => 2:12: [materials.m]: hardness must be positive, got 0
        [materials.m] | specular_ior_level = 1.5 => 2:22: [materials.m]: specular_ior_level must be in [0, 1], got 1.5
        [materials.m] | specular_tint = [1, 2, 1] => 2:17: [materials.m]: specular_tint must be in [0, 1], got 2
        [materials.m] | coat = 1.5 => 2:8: [materials.m]: coat must be in [0, 1], got 1.5
        [materials.m] | holdout = 1.5 => 2:11: [materials.m]: holdout must be in [0, 1], got 1.5
        [[mesh]] | asset = "a" | holdout = 1 => 3:11: mesh 1: holdout: invalid type: integer `1`, expected a boolean
        [[mesh]] | asset = "a" | motion = [[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]] => 3:10: mesh 1: motion must list 2 to 129 keys (the shutter's opening to its closing), got 1
        [[mesh]] | asset = "a" | motion = [[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], [1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]] => 3:10: mesh 1: motion must be invertible
        [camera] | motion = [{ position = [0, 0, 1], look_at = [0, 0, 1] }, { position = [0, 0, 1], look_at = [0, 0, 0] }] => 2:10: [camera]: motion key 1: look_at must differ from position
        [materials.m] | coat_ior = 0.5 => 2:12: [materials.m]: coat_ior must be at least 1, got 0.5
        [materials.m] | sheen = -0.5 => 2:9: [materials.m]: sheen must be in [0, 1], got -0.5
        [materials.m] | sheen_roughness = 2 => 2:19: [materials.m]: sheen_roughness must be in [0, 1], got 2
        [materials.m] | anisotropy = -0.1 => 2:14: [materials.m]: anisotropy must be in [0, 1], got -0.1
        [materials.m] | anisotropy_rotation = 1.5 => 2:23: [materials.m]: anisotropy_rotation must be in [0, 1], got 1.5
        [materials.m] | diffuse_roughness = 1.5 => 2:21: [materials.m]: diffuse_roughness must be in [0, 1], got 1.5
        [materials.m] | thin_film_thickness = -5 => 2:23: [materials.m]: thin_film_thickness must be in [0, 100000] (nm), got -5
        [materials.m] | thin_film_ior = 0.5 => 2:17: [materials.m]: thin_film_ior must be at least 1, got 0.5
        [materials.m] | sheen_tint = [1, 1.5, 1] => 2:14: [materials.m]: sheen_tint must be in [0, 1], got 1.5
        [materials.m] | specular = 0.5 | specular_ior_level = 0.5 => 3:22: [materials.m]: specular_ior_level excludes `specular` (the coating is the diffuse's own glossy layer)
        [materials.m] | volume_emission = [0, 0, -1] => 2:19: [materials.m]: volume_emission must be non-negative, got -1
        [[mesh]] | asset = "" => 2:9: mesh 1: asset must name a file or folder, got ""
        [[mesh]] | asset = "a" | scale = [1, 0, 1] => 3:9: mesh 1: scale must be non-zero, got 0
        [[mesh]] | asset = "a" | scale = 2 | matrix = [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1] => 4:10: mesh 1: matrix excludes rotate_deg, translate and scale
        [[mesh]] | asset = "a" | matrix = [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1] => 3:10: mesh 1: matrix last row must be [0, 0, 0, 1], got [0.0, 0.0, 1.0, 1.0]
        [[mesh]] | asset = "a" | matrix = [1,0,0,0, 2,0,0,0, 0,0,1,0, 0,0,0,1] => 3:10: mesh 1: matrix must be invertible
    "#,
    );
}

#[test]
fn type_and_syntax_errors_are_located() {
    assert_errors(
        r#"
        [render] | width = 1.5 => 2:9: [render]: width: invalid type: floating point `1.5`, expected u32
        [render] | width = -1 => 2:9: [render]: width: invalid value: integer `-1`, expected u32
        [[sphere]] | center = [0, 0] | radius = 1 => 2:10: sphere 1: center: invalid length 2, expected an array of length 3
        [[mesh]] | asset = "a" | scale = "big" => 3:9: mesh 1: scale: expected a number or an array [x, y, z]
        [[mesh]] | rotate_deg = [0, 0, 0] => 1:1: mesh 1: missing field `asset`
        [sky => 1:5: unclosed table, expected `]`
        [render] | width = = 1 => 2:9: extra `=`, expected nothing
    "#,
    );
}

#[test]
fn row_major_matrix_equals_rotate_translate_scale() {
    let trs = "[[mesh]]\nasset = \"a\"\nrotate_deg = [30, 45, 60]\ntranslate = [1, 2, 3]\nscale = [2, 3, 4]\n";
    let trs = parse_ok(trs).meshes[0].object_to_world;
    let (x, y, z) = (30f32.to_radians(), 45f32.to_radians(), 60f32.to_radians());
    let rotation = Mat4::from_rotation_z(z) * Mat4::from_rotation_y(y) * Mat4::from_rotation_x(x);
    let expected =
        Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0)) * rotation * Mat4::from_scale(Vec3::new(2.0, 3.0, 4.0));
    assert!(trs.abs_diff_eq(expected, 1e-6));
    let rows = trs.transpose().to_cols_array().map(|v| v.to_string()).join(", ");
    let matrix = parse_ok(&format!("[[mesh]]\nasset = \"a\"\nmatrix = [{rows}]\n")).meshes[0].object_to_world;
    assert_eq!(matrix, trs);
    assert_eq!(matrix.w_axis.truncate(), Vec3::new(1.0, 2.0, 3.0));
}

#[test]
fn load_names_an_unreadable_file() {
    let e = load(Path::new("/nonexistent/scene.toml")).expect_err("no such file");
    assert!(e.to_string().starts_with("/nonexistent/scene.toml: cannot read: "), "{e}");
    assert_eq!((e.line(), e.column()), (None, None));
}

#[test]
fn seed_is_read_as_resampled_sampling() {
    for name in ["resampled", "seed"] {
        let scene = parse_ok(&format!("[render]\nsampling = \"{name}\"\n"));
        assert_eq!(scene.render.sampling, Sampling::Resampled, "{name}");
    }
}

#[test]
fn light_sampler_is_power_unless_the_tree_is_asked_for() {
    assert_eq!(parse_ok("").render.light_sampler, crate::scene::LightSampler::Power);
    assert_eq!(parse_ok("[render]\nlight_sampler = \"tree\"\n").render.light_sampler, crate::scene::LightSampler::Tree);
    let e = crate::scene::parse("[render]\nlight_sampler = \"bvh\"\n", "s.toml", Path::new("."))
        .expect_err("unknown sampler");
    assert!(e.to_string().starts_with("s.toml:2:") && e.to_string().contains("tree"), "{e}");
}

#[test]
fn lights_parse_with_blender_defaults() {
    let s = parse_ok(
        "[[light]]\ntype = \"point\"\n\
         [[light]]\ntype = \"spot\"\ncolor = [1.0, 0.5, 0.25]\npower = 400\nradius = 0.1\nsoft_falloff = false\n\
         spot_size_deg = 30\nspot_blend = 0.5\nposition = [1, 2, 3]\ndirection = [0, 0, -2]\nvisible_to_camera = true\n\
         [[light]]\ntype = \"area\"\nshape = \"ellipse\"\nsize = 2\nsize_y = 0.5\n\
         [[light]]\ntype = \"sun\"\nstrength = 3\nangle_deg = 1.5\nmatrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n",
    );
    let [point, spot, area, sun] = &s.lights[..] else { panic!("{:?}", s.lights) };
    assert_eq!(point.shape, LightShape::Point { radius: 0.0, soft_falloff: true });
    assert_eq!((point.power, point.color, point.visible_to_camera), (10.0, Vec3::ONE, false));
    assert_eq!((point.position(), point.direction()), (Vec3::ZERO, Vec3::NEG_Y));
    assert_eq!(spot.shape, LightShape::Spot { radius: 0.1, soft_falloff: false, size_deg: 30.0, blend: 0.5 });
    assert_eq!((spot.power, spot.color, spot.visible_to_camera), (400.0, Vec3::new(1.0, 0.5, 0.25), true));
    assert_eq!((spot.position(), spot.direction()), (Vec3::new(1.0, 2.0, 3.0), Vec3::NEG_Z));
    // With `direction`, the lamp's local X is horizontal.
    assert!(spot.object_to_world.x_axis.y.abs() < 1e-6);
    assert_eq!(area.shape, LightShape::Area { shape: AreaShape::Ellipse, size: 2.0, size_y: 0.5 });
    let square = parse_ok("[[light]]\ntype = \"area\"\n").lights[0].shape;
    assert_eq!(square, LightShape::Area { shape: AreaShape::Square, size: 0.25, size_y: 0.25 });
    assert_eq!((sun.shape, sun.power, sun.direction()), (LightShape::Sun { angle_deg: 1.5 }, 3.0, Vec3::NEG_Z));
}

#[test]
fn light_errors_are_located_and_suggest() {
    assert_errors(
        r#"
        [[light]] | type = "spot" | spot_sise_deg = 30 => 3:1: unknown key `spot_sise_deg` in light 1; did you mean `spot_size_deg`?
        [[light]] | type = "pont" => 2:8: light 1: unknown type `pont`; did you mean `point`?
        [[light]] | type = "point" | [[light]] | type = "point" | angle_deg = 1 => 5:13: light 2: angle_deg only applies to type = "sun", not to type = "point"
        [[light]] | type = "sun" | power = 1 => 3:9: light 1: power only applies to point, spot and area lamps (a sun has `strength`), not to type = "sun"
        [[light]] | type = "area" | size_y = 1 => 3:10: light 1: size_y only applies to shape = "rectangle" or "ellipse"
        [[light]] | type = "spot" | spot_size_deg = 200 => 3:17: light 1: spot_size_deg must be in [1, 180], got 200
        [[light]] | type = "point" | power = -1 => 3:9: light 1: power must be non-negative, got -1
        [[light]] | type = "area" | size = 0 => 3:8: light 1: size must be positive, got 0
        [[light]] | type = "point" | direction = [0, 0, 0] => 3:13: light 1: direction must not be zero
        [[light]] | type = "point" | position = [0, 0, 0] | matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] => 4:10: light 1: matrix excludes position and direction
    "#,
    );
}

#[test]
fn instance_sets_resolve_paths_and_name_their_materials() {
    let s = parse_ok(
        "[materials.bark]\n[materials.leaf]\n[[instances]]\nasset = \"../assets/tree\"\nfile = \"trees.rtinst\"\n\
         materials = [\"leaf\", \"bark\"]\n",
    );
    assert_eq!(s.instance_sets.len(), 1);
    let set = &s.instance_sets[0];
    assert_eq!(set.asset, Path::new("/scenes/../assets/tree"));
    assert_eq!(set.file, Path::new("/scenes/trees.rtinst"));
    assert_eq!(set.materials, ["leaf", "bark"]);
    assert!(parse_ok("[[instances]]\nasset = \"a\"\nfile = \"b.rtinst\"\n").instance_sets[0].materials.is_empty());
}

#[test]
fn instance_set_mistakes_are_located() {
    assert_errors(
        r#"
        [[instances]] | asset = "a" | fille = "b.rtinst" => 3:1: unknown key `fille` in instances 1; did you mean `file`?
        [[instances]] | asset = "a" | file = "" => 3:8: instances 1: file must name a file or folder, got ""
        [[instances]] | file = "b.rtinst" => 1:1: instances 1: missing field `asset`
        [materials.bark] | [[instances]] | asset = "a" | file = "b" | materials = ["bark", "brak"] => 5:13: instances 1: materials entry 1: `brak` names no [materials.*] table; did you mean `bark`?
        | instance = [] => 2:1: unknown key `instance` in the top-level table; did you mean `instances`?
    "#,
    );
}

/// Specular IOR Level 0 leaves the diffuse without a specular layer, but a thin film keeps
/// one (over an index of 1), as Cycles sets it up; a film of 0.1 nm or less is none.
#[test]
fn a_thin_film_keeps_the_specular_layer_at_level_zero() {
    let plain = Material { specular_ior_level: 0.0, ..Material::default() };
    assert_eq!(plain.dielectric_coating(), None);
    let film = Material { thin_film_thickness: 300.0, ..plain.clone() };
    assert_eq!(film.dielectric_coating(), Some((1.0, 0.0)));
    let none = Material { thin_film_thickness: 0.1, ..plain };
    assert_eq!(none.dielectric_coating(), None);
}

/// An object's Shadow Terminator settings: Blender's defaults (Geometry Offset 0.1, Shading
/// Offset 0) where left out, on meshes and on instance files alike, each within [0, 1].
#[test]
fn shadow_terminator_settings_default_to_blenders_and_are_checked() {
    let s = parse_ok(
        "[[mesh]]\nasset = \"a\"\nshadow_terminator_shading_offset = 0.6\n[[mesh]]\nasset = \"b\"\n\
         [[instances]]\nasset = \"a\"\nfile = \"b.rtinst\"\nshadow_terminator_geometry_offset = 0\n",
    );
    let shifted = ShadowTerminator { geometry_offset: 0.1, shading_offset: 0.6 };
    assert_eq!(s.meshes[0].shadow_terminator, shifted);
    assert_eq!(s.meshes[1].shadow_terminator, ShadowTerminator::default());
    assert_eq!(s.instance_sets[0].shadow_terminator, ShadowTerminator { geometry_offset: 0.0, shading_offset: 0.0 });
    // Cycles' frequency multiplier: 1 / (1 - 0.6 / 2), and 1 (no shift) by default.
    assert!((shifted.frequency_multiplier() - 1.0 / 0.7).abs() < 1e-6);
    assert_eq!(ShadowTerminator::default().frequency_multiplier(), 1.0);
    assert_errors(
        r#"
        [[mesh]] | asset = "a" | shadow_terminator_shading_offset = 1.5 => 3:36: mesh 1: shadow_terminator_shading_offset must be in [0, 1], got 1.5
        [[mesh]] | asset = "a" | shadow_terminator_geometry_offset = -0.1 => 3:37: mesh 1: shadow_terminator_geometry_offset must be in [0, 1], got -0.1
        [[instances]] | asset = "a" | file = "b" | shadow_terminator_shading_offset = nan => 4:36: instances 1: shadow_terminator_shading_offset must be finite, got NaN
        [[mesh]] | asset = "a" | shadow_terminator_offset = 0.5 => 3:1: unknown key `shadow_terminator_offset` in mesh 1; did you mean `shadow_terminator_shading_offset`?
        [[instances]] | asset = "a" | file = "b" | shadow_terminator_shading_ofset = 0.5 => 4:1: unknown key `shadow_terminator_shading_ofset` in instances 1; did you mean `shadow_terminator_shading_offset`?
    "#,
    );
}
