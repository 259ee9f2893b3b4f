//! `rt bench`: convergence, the reference cache, pipelines that agree, and reports that parse.
//! Tiny on purpose (lavapipe in CI): 32×32 images, few samples, few knobs, one or two repeats.

use crate::common;

use common::paired;
use common::{gpu, repo, temp_dir, write};
use rt::bvh::BuildQuality;
use rt::gpu::GpuTimer;
use rt::render::{RenderRequest, Session};
use rt_bench::knobs::select;
use rt_bench::model::log_log_slope;
use rt_bench::reference::{ReferenceOrigin, ReferenceSettings, obtain, reference_trial};
use rt_bench::report::{MEASUREMENT_COLUMNS, SETTING_COLUMNS};
use rt_bench::sweep::{SweepOptions, run};
use std::path::Path;

#[test]
fn rmse_falls_at_least_as_one_over_root_spp_on_a_diffuse_scene() {
    let scene = rt::scene::default_scene().unwrap_or_else(|e| panic!("{e}"));
    let levels = vec![4, 16, 64];
    let options = SweepOptions {
        size: (32, 32),
        levels: levels.clone(),
        repeats: 2,
        // As many bounces as the scene's renders: no bias, so all the error is noise.
        reference: ReferenceSettings { spp: 512, max_bounces: scene.render.max_bounces },
        cache_dir: temp_dir("slope"),
        progress: false,
    };
    let knobs = select(&levels, &["spp".to_string()]).expect("the spp knob");
    let sweep = run(gpu(), &scene, &knobs, &options).unwrap_or_else(|e| panic!("{e:#}"));
    let ladder = &sweep.knobs[0].settings[0].levels;
    assert_eq!(ladder.iter().map(|m| m.spp).collect::<Vec<_>>(), [4, 8, 16, 32, 64]);
    let points: Vec<(f64, f64)> = ladder.iter().map(|m| (m.spp as f64, m.error.rmse())).collect();
    let slope = log_log_slope(&points).expect("slope");
    // Each level's MSE is a mean over 1,024 pixels and 2 seeds: with the Cornell box's
    // tails, within ~10 % (1σ), so ln RMSE within ~0.05. Least squares over five levels
    // ln 2 apart (Σ(x − x̄)² = 10 ln² 2 ≈ 4.8) puts the slope within 0.05 / √4.8 ≈ 0.023
    // (1σ). Independent samples give -0.5; rt's scrambled Sobol points converge faster
    // where the integrand is smooth in their dimensions (at best -0.75 for Owen-scrambled
    // nets), and never slower: measured -0.64 here (-0.50 with independent samples).
    assert!((-0.85..=-0.45).contains(&slope), "log-log slope {slope:.3}, expected -0.45 to -0.85: {points:?}");
    let fit = sweep.knobs[0].settings[0].fit.expect("fit");
    assert_eq!(fit.bias2, 0.0, "an unbiased setting needs no error floor: {fit:?}");
}

const SCENE: &str = r#"
[camera]
position = [0.0, 1.0, 3.0]
look_at = [0.0, 0.5, 0.0]
[sky]
kind = "uniform"
color = [0.6, 0.7, 0.9]
[materials.grey]
base_color = [0.5, 0.5, 0.5]
[[mesh]]
asset = "floor.obj"
[[sphere]]
center = [0.0, 0.5, 0.0]
radius = 0.5
material = "grey"
"#;

const FLOOR: &str = "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 3 2\nf 1 4 3\n";

fn reference_of(scene_path: &Path, cache: &Path) -> (ReferenceOrigin, Vec<[f32; 3]>) {
    let scene = rt::scene::load(scene_path).unwrap_or_else(|e| panic!("{e}"));
    let settings = ReferenceSettings { spp: 8, max_bounces: 4 };
    let trial = reference_trial(&scene, (16, 16), settings);
    let mut renderer = Session::open(gpu(), trial.scene.clone(), BuildQuality::Medium).expect("renderer");
    let reference =
        obtain(&mut renderer, &trial, settings, cache, &GpuTimer::new(gpu())).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(reference.path.starts_with(cache));
    (reference.origin, reference.image.pixels)
}

#[test]
fn reference_is_reused_until_the_scene_or_an_asset_changes() {
    let dir = temp_dir("reference");
    let (scene_path, cache) = (dir.join("scene.toml"), dir.join("cache"));
    write(&scene_path, SCENE);
    write(&dir.join("floor.obj"), FLOOR);
    let (first, pixels) = reference_of(&scene_path, &cache);
    assert!(matches!(first, ReferenceOrigin::Rendered(_)), "{first:?}");
    let (again, cached) = reference_of(&scene_path, &cache);
    assert_eq!(again, ReferenceOrigin::Cached);
    assert_eq!(pixels, cached, "the cached reference is the rendered one");
    // A comment changes no pixel: still cached.
    write(&scene_path, &format!("# a note\n{SCENE}"));
    assert_eq!(reference_of(&scene_path, &cache).0, ReferenceOrigin::Cached);
    write(&scene_path, &SCENE.replace("[0.5, 0.5, 0.5]", "[0.8, 0.2, 0.2]"));
    assert!(matches!(reference_of(&scene_path, &cache).0, ReferenceOrigin::Rendered(_)), "scene edited");
    write(&dir.join("floor.obj"), &FLOOR.replace("v -2 0 -2", "v -3 0 -2"));
    assert!(matches!(reference_of(&scene_path, &cache).0, ReferenceOrigin::Rendered(_)), "asset edited");
    let _ = std::fs::remove_dir_all(dir);
}

/// Every scene of `scenes/` rendered with its specialised pipeline and with the
/// all-features pipeline agrees in each colour channel, over the image and each quarter,
/// within its noise (`common::paired`); and the comparison sees a 10 % error in one
/// channel, which a luminance test can miss.
#[test]
fn specialised_and_all_features_pipelines_agree() {
    // |z| bound: with 15 degrees of freedom, a false failure among these 195 comparisons
    // has a chance of about 10⁻³. (On lavapipe a scene takes ~35 s, most of it compiling
    // its two pipelines.)
    const BOUND: f64 = 7.0;
    let mut compared = 0;
    for path in common::scene_files() {
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let started = std::time::Instant::now();
        let scene = rt::scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut renderer = Session::open(gpu(), scene, BuildQuality::Medium).expect("renderer");
        let own = renderer.features();
        let all = common::all_features_but_node_graphs(own, renderer.scene());
        if own == all {
            println!("{name}: its own pipeline is the all-features one");
            continue;
        }
        let mut request = RenderRequest::from_scene(renderer.scene());
        (request.width, request.height, request.spp) = (32, 32, 8);
        let specialised = paired::renders(&mut renderer, &request, own, 16);
        let everything = paired::renders(&mut renderer, &request, all, 16);
        let (z, at) = paired::worst_z(&specialised, &everything);
        println!("{name}: worst |z| {z:.2} at {at} ({:.1?})", started.elapsed());
        assert!(z < BOUND, "{name}: specialised and all-features images differ at {at}: |z| {z:.1}");
        let (off, _) = paired::worst_z(&specialised, &paired::scaled(&everything, 2, 1.1));
        assert!(off > BOUND, "{name}: a 10 % error in blue reads |z| {off:.1} only");
        compared += 1;
    }
    assert!(compared >= 10, "only {compared} scenes leave an effect out");
}

#[test]
fn all_features_pipeline_stays_finite_without_emitters() {
    // The sunlit pillars emit nothing: the emission code of the all-features pipeline
    // must not divide by the total emitted power, which is 0.
    let scene = rt::scene::load(&repo().join("scenes/specular_pillars.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut renderer = Session::open(gpu(), scene, BuildQuality::Medium).expect("renderer");
    let own = renderer.features();
    assert!(!own.emission);
    let mut request = RenderRequest::from_scene(renderer.scene());
    (request.width, request.height, request.spp) = (24, 16, 8);
    request.features = Some(common::all_features_but_node_graphs(own, renderer.scene()));
    let (_, report) = renderer.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(report.dropped.is_clean(), "{}", report.dropped);
}

fn csv_rows(path: &Path, header: &str) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(header), "{}: header", path.display());
    let columns = header.split(',').count();
    let rows: Vec<Vec<String>> = lines.map(|l| l.split(',').map(str::to_string).collect()).collect();
    assert!(!rows.is_empty(), "{}: no rows", path.display());
    for row in &rows {
        assert_eq!(row.len(), columns, "{}: {row:?}", path.display());
    }
    rows
}

#[test]
fn report_files_are_written_and_parse() {
    let out = temp_dir("report");
    let scene = rt::scene::default_scene().unwrap_or_else(|e| panic!("{e}"));
    let options = common::small_accuracy_options(&["sampling", "samples-per-dispatch"], out.clone());
    let summary = rt_bench::accuracy(gpu(), &scene, &options).unwrap_or_else(|e| panic!("{e:#}"));
    let report = std::fs::read_to_string(&summary.report).expect("report.md");
    assert!(report.contains(&gpu().adapter_info.name), "the report names the adapter");
    assert!(report.contains("## sampling") && report.contains("## samples-per-dispatch"));

    let rows = csv_rows(&out.join("measurements.csv"), MEASUREMENT_COLUMNS);
    // The baseline and 2 + 5 settings at 3 levels each.
    assert_eq!(rows.len(), 8 * 3);
    for row in &rows {
        for value in &row[3..12] {
            let v: f64 = value.parse().unwrap_or_else(|_| panic!("not a number: {value:?} in {row:?}"));
            assert!(v.is_finite(), "{row:?}");
        }
    }
    let settings = csv_rows(&out.join("settings.csv"), SETTING_COLUMNS);
    assert_eq!(settings.len(), 7);
    assert!(settings.iter().all(|r| r[9] == "true" || r[9] == "false"));

    for knob in ["sampling", "samples-per-dispatch"] {
        let png = image::open(out.join(format!("{knob}.png"))).unwrap_or_else(|e| panic!("{knob}.png: {e}"));
        assert!(png.width() > 100 && png.height() > 100);
    }
    assert!(select(&[1, 2, 4], &["nope".into()]).is_err_and(|e| e.contains("samples-per-dispatch")));
    let _ = std::fs::remove_dir_all(out);
}

/// The `clean-image` knob is one setting per way to a clean image, each applying what
/// its label says (and nothing of the others).
#[test]
fn clean_image_knob_sets_adaptive_and_denoise_together() {
    let knobs = select(&[1, 2, 4], &["clean-image".to_string()]).expect("the clean-image knob");
    assert_eq!(knobs.len(), 1);
    let labels: Vec<&str> = knobs[0].settings.iter().map(|s| s.label.as_str()).collect();
    assert_eq!(labels, ["raw", "adaptive", "denoised", "adaptive+denoised"]);
    let scene = rt::scene::default_scene().unwrap_or_else(|e| panic!("{e}"));
    let base = rt_bench::knobs::Trial::baseline(&scene, (32, 32));
    let applied: Vec<(bool, bool, bool)> = knobs[0]
        .settings
        .iter()
        .map(|s| {
            let t = s.trial(&base);
            (t.request.noise_threshold > 0.0, t.denoise, t.request.aovs)
        })
        .collect();
    assert_eq!(applied, [(false, false, false), (true, false, false), (false, true, true), (true, true, true)]);
    assert!(knobs[0].settings[0].trial(&base).same_as(&base), "raw is the scene's own settings (measured once)");
}

/// With a denoiser, the `clean-image` section has a row per setting with its time to the
/// RMSE target and to SSIM 0.99, each a time, `~` a time, or ∞.
#[cfg(feature = "denoise")]
#[test]
fn clean_image_report_prices_each_way_to_both_targets() {
    let out = temp_dir("clean-image");
    let scene = rt::scene::default_scene().unwrap_or_else(|e| panic!("{e}"));
    let options = common::small_accuracy_options(&["clean-image"], out.clone());
    let summary = rt_bench::accuracy(gpu(), &scene, &options).unwrap_or_else(|e| panic!("{e:#}"));
    let report = std::fs::read_to_string(&summary.report).expect("report.md");
    let section: Vec<&str> = report.lines().skip_while(|l| *l != "## clean-image").collect();
    assert!(!section.is_empty() && !report.contains("cannot denoise"), "no clean-image section:\n{report}");
    let header = section.iter().find(|l| l.starts_with("| setting |")).unwrap_or_else(|| panic!("{report}"));
    let columns: Vec<&str> = header.split('|').map(str::trim).collect();
    let to_rmse = columns.iter().position(|c| *c == "time to 1.00 %").unwrap_or_else(|| panic!("{header}"));
    let to_ssim = columns.iter().position(|c| *c == "time to SSIM 0.99").unwrap_or_else(|| panic!("{header}"));
    let rows: Vec<Vec<&str>> = section
        .iter()
        .skip_while(|l| !l.starts_with("|---"))
        .skip(1)
        .take_while(|l| l.starts_with('|'))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    let labels: Vec<&str> = rows.iter().map(|r| r[1]).collect();
    assert_eq!(labels, ["raw", "adaptive", "denoised", "adaptive+denoised"], "{report}");
    let is_time = |cell: &str| {
        let t = cell.trim_start_matches('~');
        cell == "∞" || t.split(' ').next().is_some_and(|v| v.parse::<f64>().is_ok_and(|v| v > 0.0))
    };
    for row in &rows {
        assert_eq!(row.len(), columns.len(), "{row:?}");
        assert!(is_time(row[to_rmse]) && is_time(row[to_ssim]), "{row:?}");
    }
    let settings = csv_rows(&out.join("settings.csv"), SETTING_COLUMNS);
    assert_eq!(settings.len(), 4, "a row per setting of the one knob");
    let _ = std::fs::remove_dir_all(out);
}
