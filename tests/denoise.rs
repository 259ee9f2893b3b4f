//! Denoising with Open Image Denoise: a 16-sample image denoised is closer to the
//! converged one than the raw image at twice the samples and looks closer (SSIM) than
//! the raw image at four times the samples; a missing library is a clear message, not a
//! crash (nor a loader's error before rt starts). Twice, not four times, for the error:
//! rt's stratified sampler makes raw images converge faster than 1/√N, and on the
//! `lamps` scene 64 raw samples come within noise of the denoised 16.

use crate::common;

use common::temp_dir;
use std::process::Command;

#[cfg(feature = "denoise")]
#[test]
fn sixteen_samples_denoised_beat_more_samples_raw() {
    use common::{gpu, repo};
    use rt::bvh::BuildQuality;
    use rt::render::{Image, RenderRequest, Session};
    let mut denoiser = rt::denoise::Denoiser::new(rt::denoise::DenoiseDevice::Auto).unwrap_or_else(|e| panic!("{e:#}"));
    for name in ["cornell_box", "cornell_glass", "lamps"] {
        let scene = rt::scene::load(&repo().join(format!("scenes/{name}.toml"))).unwrap_or_else(|e| panic!("{e}"));
        let mut session = Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
        let base = RenderRequest { width: 64, height: 64, ..RenderRequest::from_scene(session.scene()) };
        let mut render = |spp: u32, seed: u32, aovs: bool| -> Image {
            let request = RenderRequest { spp, seed, aovs, ..base.clone() };
            session.render(&request, None).unwrap_or_else(|e| panic!("{name}: {e:#}")).0
        };
        // The reference as two halves of independent samples: their difference measures
        // its own noise, taken off every error (as `rt bench accuracy` does).
        let (half_a, half_b) = (render(192, 1, false), render(192, 4, false));
        let converged: Vec<[f32; 3]> =
            half_a.pixels.iter().zip(&half_b.pixels).map(|(a, b)| [0, 1, 2].map(|c| 0.5 * (a[c] + b[c]))).collect();
        let own_noise = common::display_mse(&half_a.pixels, &half_b.pixels) / 4.0;
        let error = |pixels: &[[f32; 3]]| (common::display_mse(pixels, &converged) - own_noise).max(0.0).sqrt();
        let (raw, raw_4x) = (render(32, 2, false), render(64, 5, false));
        let few = render(16, 3, true);
        let aovs = session.aovs().unwrap_or_else(|e| panic!("{e:#}"));
        let denoised = denoiser.denoise(&few, &aovs).unwrap_or_else(|e| panic!("{name}: {e:#}"));
        let (raw_error, denoised_error, noisy_error) = (error(&raw.pixels), error(&denoised), error(&few.pixels));
        eprintln!(
            "{name}: display RMSE against 384 spp (its own noise {:.2} taken off): 16 spp {noisy_error:.2}, \
             16 spp denoised ({}) {denoised_error:.2}, 32 spp {raw_error:.2}, 64 spp {:.2}",
            own_noise.sqrt(),
            denoiser.device(),
            error(&raw_4x.pixels)
        );
        assert!(denoised_error < raw_error, "{name}: denoised 16 spp {denoised_error:.2} vs raw 32 spp {raw_error:.2}");
        // The perceptual figure agrees: SSIM of the display luma against the converged image.
        let luma = |pixels: &[[f32; 3]]| rt_bench::metrics::display_luma(pixels, 0.0);
        let ssim = |pixels: &[[f32; 3]]| rt_bench::ssim::ssim(&luma(pixels), &luma(&converged), 64, 64);
        let (raw_ssim, denoised_ssim, noisy_ssim) = (ssim(&raw_4x.pixels), ssim(&denoised), ssim(&few.pixels));
        eprintln!("{name}: SSIM 16 spp {noisy_ssim:.4}, 16 spp denoised {denoised_ssim:.4}, 64 spp {raw_ssim:.4}");
        assert!(
            denoised_ssim > raw_ssim,
            "{name}: SSIM denoised 16 spp {denoised_ssim:.4} vs raw 64 spp {raw_ssim:.4}"
        );
    }
}

/// Open Image Denoise loads its devices from beside its library: with the library found
/// (in `$OIDN_DIR/lib`) but no device beside it, `--denoise` must say what is missing,
/// before rendering.
#[cfg(feature = "denoise")]
#[test]
fn missing_device_libraries_are_a_clear_message() {
    let installed = std::path::PathBuf::from(env!("OIDN_DIR")).join("lib");
    let lib = temp_dir("oidn-missing").join("lib");
    std::fs::create_dir_all(&lib).expect("dir");
    for name in ["libOpenImageDenoise.so.2", "libOpenImageDenoise_core.so.2.5.1", "libtbb.so.12"] {
        let _ = std::fs::remove_file(lib.join(name));
        std::os::unix::fs::symlink(installed.join(name), lib.join(name)).expect("link");
    }
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--size", "8x8", "--spp", "1", "--denoise", "-o"])
        .arg(lib.join("x.png"))
        .env("OIDN_DIR", lib.parent().expect("the lib folder's parent"))
        .output()
        .expect("run rt");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("Open Image Denoise could make no device") && stderr.contains("scripts/fetch_oidn"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked") && !lib.join("x.png").exists(), "{stderr}");
}

/// `--denoise-device cuda` where Open Image Denoise has no CUDA device is an error that
/// says so, before rendering; `cpu` and `auto` say which device they took.
#[cfg(feature = "denoise")]
#[test]
fn denoise_device_is_chosen_and_named() {
    let has_cuda = rt::denoise::physical_devices().unwrap_or_else(|e| panic!("{e:#}")).iter().any(|d| d.kind == "CUDA");
    let dir = temp_dir("denoise-device");
    let run = |device: &str| {
        let png = dir.join(format!("{device}.png"));
        let out = Command::new(env!("CARGO_BIN_EXE_rt"))
            .args(["render", "--size", "8x8", "--spp", "2", "--denoise", "--denoise-device", device, "-o"])
            .arg(&png)
            .output()
            .expect("run rt");
        (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned(), png.exists())
    };
    let (code, stderr, written) = run("cpu");
    assert_eq!(code, Some(0), "{stderr}");
    assert!(written && stderr.contains("denoising with Open Image Denoise on CPU"), "{stderr}");
    let (code, stderr, _) = run("auto");
    assert_eq!(code, Some(0), "{stderr}");
    let expected = if has_cuda { "on CUDA" } else { "on CPU" };
    assert!(stderr.contains(expected), "auto: {stderr}");
    if !has_cuda {
        assert!(stderr.contains("auto: no CUDA device"), "auto says why it took the CPU: {stderr}");
        let (code, stderr, written) = run("cuda");
        assert_eq!(code, Some(1), "{stderr}");
        assert!(stderr.contains("found no CUDA device") && stderr.contains("--denoise-device cpu"), "{stderr}");
        assert!(!written && !stderr.contains("panicked") && !stderr.contains("GPU:"), "before rendering: {stderr}");
    }
    // The device is an option of --denoise.
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--denoise-device", "cpu", "-o"])
        .arg(dir.join("x.png"))
        .output()
        .expect("run rt");
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
    let _ = std::fs::remove_dir_all(dir);
}

/// `rt bench denoise` times each device it has and says what it timed.
#[cfg(feature = "denoise")]
#[test]
fn bench_denoise_prints_a_row_per_device() {
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["bench", "denoise", "--size", "48x32", "--runs", "2", "--spp", "2"])
        .output()
        .expect("run rt");
    let (stdout, stderr) = (String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert_eq!(out.status.code(), Some(0), "{stdout}\n{stderr}");
    for line in ["Open Image Denoise devices found: ", "frame: 48x32", "| device | first run | median of 2 |"] {
        assert!(stdout.contains(line), "no {line:?} in:\n{stdout}");
    }
    let row = stdout.lines().find(|l| l.starts_with("| CPU")).unwrap_or_else(|| panic!("no CPU row:\n{stdout}"));
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    let ms = |cell: &str| cell.strip_suffix(" ms").and_then(|v| v.parse::<f64>().ok());
    let (median, fastest) = (ms(cells[3]), ms(cells[4]));
    assert!(median.zip(fastest).is_some_and(|(m, f)| f > 0.0 && f <= m), "{row}");
}

#[cfg(not(feature = "denoise"))]
#[test]
fn a_build_without_open_image_denoise_says_how_to_get_it() {
    let out = Command::new(env!("CARGO_BIN_EXE_rt"))
        .args(["render", "--size", "8x8", "--spp", "1", "--denoise", "-o"])
        .arg(temp_dir("no-oidn").join("x.png"))
        .output()
        .expect("run rt");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("built without Open Image Denoise") && stderr.contains("--features denoise"), "{stderr}");
}

/// `rt bench accuracy` prices denoising and adaptive sampling as knobs.
#[cfg(feature = "denoise")]
#[test]
fn bench_accuracy_has_denoise_and_adaptive_knobs() {
    let out = temp_dir("bench-knobs");
    let scene = rt::scene::default_scene().unwrap_or_else(|e| panic!("{e}"));
    let options = common::small_accuracy_options(&["denoise", "adaptive"], out.clone());
    let summary = rt_bench::accuracy(common::gpu(), &scene, &options).unwrap_or_else(|e| panic!("{e:#}"));
    let report = std::fs::read_to_string(&summary.report).expect("report.md");
    for section in ["## denoise", "## adaptive", "| on |", "| 0.05 |", "time to SSIM 0.99", "| raw needs |"] {
        assert!(report.contains(section), "no {section:?} in the report:\n{report}");
    }
    // The denoise knob's equal-quality table: a row per level of the denoised setting.
    let rows = report.lines().skip_while(|l| !l.contains("| raw needs |")).skip(2).take_while(|l| l.starts_with('|'));
    assert_eq!(rows.count(), 3, "{report}");
    let settings = std::fs::read_to_string(out.join("settings.csv")).expect("settings.csv");
    let header: Vec<&str> = settings.lines().next().unwrap_or_default().split(',').collect();
    let column = header.iter().position(|c| *c == "top_ssim").expect("a top_ssim column");
    for row in settings.lines().skip(1) {
        let ssim: f64 = row.split(',').nth(column).and_then(|v| v.parse().ok()).expect("an SSIM");
        assert!(ssim > 0.0 && ssim <= 1.0, "{row}");
    }
    assert!(!report.contains("cannot denoise"), "the denoise knob was skipped:\n{report}");
    let _ = std::fs::remove_dir_all(out);
}

/// A noisy gradient and its guides (a flat albedo, normals facing the camera), made on
/// the CPU: `seed` changes the noise.
#[cfg(feature = "denoise")]
fn noisy_frame(width: u32, height: u32, seed: u32) -> (rt::render::Image, rt::render::Aovs) {
    let pixels = (width * height) as usize;
    let mut state = seed.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let mut noise = move || {
        state = state.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
        (state >> 8) as f32 / (1u32 << 24) as f32
    };
    let pixels_rgb: Vec<[f32; 3]> = (0..pixels)
        .map(|i| {
            let x = (i as u32 % width) as f32 / width as f32;
            [0, 1, 2].map(|c| (0.2 + 0.6 * x + 0.1 * c as f32) * 2.0 * noise())
        })
        .collect();
    let image = rt::render::Image {
        width,
        height,
        samples: 4,
        pixels: pixels_rgb,
        std_error: vec![0.1; pixels],
        sample_counts: vec![4; pixels],
        alpha: None,
    };
    let aovs = rt::render::Aovs {
        width,
        height,
        albedo: vec![[0.8, 0.7, 0.6]; pixels],
        normal: vec![[0.0, 0.0, 1.0]; pixels],
        depth: vec![1.0; pixels],
        ..Default::default()
    };
    (image, aovs)
}

/// The filters are kept while the size stays and made again when it changes; a kept
/// filter denoises each new image as a fresh denoiser does (no pixel of an earlier image
/// stays behind in its buffers).
#[cfg(feature = "denoise")]
#[test]
fn filters_are_kept_between_denoises_of_one_size() {
    use rt::denoise::{DenoiseDevice, Denoiser};
    let mut kept = Denoiser::new(DenoiseDevice::Cpu).unwrap_or_else(|e| panic!("{e:#}"));
    let fresh = |image: &rt::render::Image, aovs: &rt::render::Aovs| {
        let mut denoiser = Denoiser::new(DenoiseDevice::Cpu).unwrap_or_else(|e| panic!("{e:#}"));
        denoiser.denoise(image, aovs).unwrap_or_else(|e| panic!("{e:#}"))
    };
    let mut previous: Option<Vec<[f32; 3]>> = None;
    for (i, (w, h, seed)) in [(40, 24, 1), (40, 24, 2), (40, 24, 3), (24, 40, 4), (24, 40, 5)].into_iter().enumerate() {
        let (image, aovs) = noisy_frame(w, h, seed);
        let got = kept.denoise(&image, &aovs).unwrap_or_else(|e| panic!("{e:#}"));
        let expected = fresh(&image, &aovs);
        let worst =
            got.iter().zip(&expected).flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs())).fold(0.0, f32::max);
        // The same filter on the same input: equal but for the order of float sums, if any.
        assert!(worst < 1e-4, "image {i} ({w}x{h}): kept filters differ from fresh ones by {worst}");
        let raw_error = image.pixels.iter().zip(&got).map(|(a, b)| (a[0] - b[0]).abs()).sum::<f32>();
        assert!(raw_error > 1.0, "image {i}: the denoiser changed nothing");
        if let Some(previous) = &previous {
            assert_ne!(previous, &got, "image {i}: the last image's result came back");
        }
        previous = Some(got);
        let builds = if i < 3 { 1 } else { 2 };
        assert_eq!(kept.filter_builds(), builds, "image {i} ({w}x{h}): filters made {} times", kept.filter_builds());
    }
    kept.release_filters();
    let (image, aovs) = noisy_frame(24, 40, 6);
    kept.denoise(&image, &aovs).unwrap_or_else(|e| panic!("{e:#}"));
    assert_eq!(kept.filter_builds(), 3, "released filters are made again");
}

/// rt loads Open Image Denoise when it denoises, not when it starts: with the library gone
/// (`OIDN_DIR` at a folder without it, nothing on the loader's path), a plain render still
/// works and `--denoise` is an error naming the library, where it looked and how to get it.
#[cfg(feature = "denoise")]
#[test]
fn a_missing_library_stops_only_denoising_and_says_how_to_get_it() {
    let dir = temp_dir("oidn-gone");
    let run = |args: &[&str], output: &str| {
        let out = Command::new(env!("CARGO_BIN_EXE_rt"))
            .args(args)
            .arg(dir.join(output))
            .env("OIDN_DIR", &dir)
            .env_remove("LD_LIBRARY_PATH")
            .output()
            .expect("run rt");
        (out.status.code(), String::from_utf8_lossy(&out.stderr).into_owned(), dir.join(output).exists())
    };
    let (code, stderr, written) = run(&["render", "--size", "8x8", "--spp", "1", "-o"], "plain.png");
    assert!(!stderr.contains("error while loading shared libraries"), "{stderr}");
    assert_eq!(code, Some(0), "a render without --denoise needs no denoiser: {stderr}");
    assert!(written, "{stderr}");
    let (code, stderr, written) = run(&["render", "--size", "8x8", "--spp", "1", "--denoise", "-o"], "denoised.png");
    assert_eq!(code, Some(1), "{stderr}");
    let missing = dir.join("lib").join("libOpenImageDenoise.so.2");
    for part in ["Open Image Denoise is missing", &missing.display().to_string(), "scripts/fetch_oidn", "OIDN_DIR"] {
        assert!(stderr.contains(part), "no {part:?} in: {stderr}");
    }
    assert!(!written && !stderr.contains("panicked") && !stderr.contains("GPU:"), "before rendering: {stderr}");
    let _ = std::fs::remove_dir_all(dir);
}
