//! Exact sample-range splits: parts of a render (`rt render --sample-range`), merged by
//! `rt merge`, are the image one render gives, bit for bit, however the samples were
//! split, dispatched and spread over lanes; parts of different renders are refused.

use crate::common;

use common::bounded::{Outcome, rt};
use common::{empty_temp_dir, gpu};
use rt::bvh::BuildQuality;
use rt::render::exact::ExactSums;
use rt::render::part::{self, PartHeader};
use rt::render::{Aovs, Image, RenderRequest, Session};
use std::path::Path;
use std::time::Duration;

/// The built-in Cornell box with a transparent film: radiance, alpha and AOVs all count.
fn session() -> Session<'static> {
    let mut scene = rt::scene::default_scene().unwrap_or_else(|e| panic!("{e:#}"));
    scene.render.transparent = true;
    scene.render.noise_threshold = 0.0;
    Session::open(gpu(), scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"))
}

fn request(session: &Session, samples: std::ops::Range<u32>, dispatch: u32, lanes: u32) -> RenderRequest {
    RenderRequest {
        width: 20,
        height: 16,
        spp: samples.len() as u32,
        first_sample: samples.start,
        seed: 5,
        aovs: true,
        exact_sums: true,
        samples_per_dispatch: Some(dispatch),
        sample_lanes: Some(lanes),
        ..RenderRequest::from_scene(session.scene())
    }
}

fn sums(session: &Session) -> ExactSums {
    session.exact_sums().unwrap_or_else(|e| panic!("{e:#}")).expect("the request asked for exact sums")
}

/// Asserts `a` and `b` hold the same bits, saying how many values differ and the first.
fn assert_bits(case: &str, what: &str, a: &[u32], b: &[u32]) {
    assert_eq!(a.len(), b.len(), "{case}: {what}: lengths");
    let differ: Vec<usize> = (0..a.len()).filter(|&i| a[i] != b[i]).collect();
    if let Some(&i) = differ.first() {
        let (x, y) = (f32::from_bits(a[i]), f32::from_bits(b[i]));
        panic!("{case}: {what}: {} of {} values differ, the first at {i}: {x} vs {y}", differ.len(), a.len());
    }
}

/// Asserts two images and their AOVs are the same bit for bit.
fn assert_same(case: &str, (a, a_aovs): (&Image, &Aovs), (b, b_aovs): (&Image, &Aovs)) {
    let bits = |v: &[[f32; 3]]| v.iter().flat_map(|p| p.map(f32::to_bits)).collect::<Vec<_>>();
    let scalar_bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_bits(case, "radiance", &bits(&a.pixels), &bits(&b.pixels));
    let (a_alpha, b_alpha) = (a.alpha.as_deref().expect("alpha"), b.alpha.as_deref().expect("alpha"));
    assert_bits(case, "alpha", &scalar_bits(a_alpha), &scalar_bits(b_alpha));
    assert_bits(case, "standard error", &scalar_bits(&a.std_error), &scalar_bits(&b.std_error));
    assert_eq!(a.sample_counts, b.sample_counts, "{case}: sample counts");
    for (name, x, y) in [
        ("albedo", &a_aovs.albedo, &b_aovs.albedo),
        ("normal", &a_aovs.normal, &b_aovs.normal),
        ("position", &a_aovs.position, &b_aovs.position),
        ("emission", &a_aovs.emission, &b_aovs.emission),
        ("diffuse colour", &a_aovs.diffuse_color, &b_aovs.diffuse_color),
    ] {
        assert_bits(case, name, &bits(x), &bits(y));
    }
    assert_bits(case, "depth", &scalar_bits(&a_aovs.depth), &scalar_bits(&b_aovs.depth));
}

/// The split points of 0..`spp` a small generator draws, and each part's dispatch size and lanes.
fn random_split(state: &mut u64, spp: u32) -> Vec<(std::ops::Range<u32>, u32, u32)> {
    let mut next = |n: u32| {
        *state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        ((*state >> 33) % n as u64) as u32
    };
    let mut parts = Vec::new();
    let mut start = 0;
    while start < spp {
        let end = (start + 1 + next(spp / 2)).min(spp);
        parts.push((start..end, 1 + next(4), 1 + next(3)));
        start = end;
    }
    parts
}

#[test]
fn random_splits_merge_into_the_whole_render_bit_for_bit() {
    let spp = 13;
    let mut session = session();
    session.render(&request(&session, 0..spp, 4, 1), None).unwrap_or_else(|e| panic!("{e:#}"));
    let whole = sums(&session);
    let (image, aovs) = (whole.image(spp, true), whole.aovs().expect("AOV sums"));
    assert!(image.alpha.as_ref().is_some_and(|a| a.iter().any(|&v| v < 1.0)), "the film leaves some pixels open");
    let mut state = 0x5eed;
    for split in 0..4 {
        let parts = random_split(&mut state, spp);
        let mut merged: Option<ExactSums> = None;
        for (samples, dispatch, lanes) in &parts {
            session
                .render(&request(&session, samples.clone(), *dispatch, *lanes), None)
                .unwrap_or_else(|e| panic!("{e:#}"));
            let part = sums(&session);
            match &mut merged {
                Some(m) => m.add(&part),
                None => merged = Some(part),
            }
        }
        let merged = merged.expect("one part at least");
        let case = format!("split {split}: {parts:?}");
        assert_same(&case, (&image, &aovs), (&merged.image(spp, true), &merged.aovs().expect("AOV sums")));
    }
    // Not vacuous: a part alone is another image.
    session.render(&request(&session, 0..6, 6, 1), None).unwrap_or_else(|e| panic!("{e:#}"));
    assert_ne!(sums(&session).image(6, true).pixels, image.pixels, "six samples show more noise than thirteen");
}

fn run(dir: &Path, args: &[&str]) -> Outcome {
    rt(dir, args, Duration::from_secs(300))
}

#[test]
fn rt_merge_writes_the_files_rt_render_writes_and_refuses_other_renders_parts() {
    let dir = empty_temp_dir("sample-range");
    let size = ["--size", "24x20", "--seed", "3", "--transparent", "--progress", "none"];
    let with = |extra: &[&'static str]| [extra, &size[..]].concat();
    run(&dir, &[&["render", "-o", "whole.exr", "--spp", "7", "--aovs"][..], &size].concat()).expect("whole", 0);
    run(&dir, &[&["render", "-o", "whole.png", "--spp", "7"][..], &size].concat()).expect("whole png", 0);
    for (range, aovs) in [("0..3", true), ("3..7", true), ("0..5", false), ("5..7", false)] {
        let out = format!("{}{range}.exr", if aovs { "aov" } else { "plain" });
        let mut args = vec!["render", "-o", &out, "--sample-range", range];
        if aovs {
            args.push("--aovs");
        }
        run(&dir, &[&args[..], &size[..]].concat()).expect(&out, 0);
    }
    run(&dir, &["merge", "aov3..7.exr", "aov0..3.exr", "-o", "merged.exr"]).expect("merge exr", 0);
    run(&dir, &["merge", "plain0..5.exr", "plain5..7.exr", "-o", "merged.png"]).expect("merge png", 0);
    let read = |name: &str| std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(read("whole.exr") == read("merged.exr"), "the merged EXR (with its AOV layers) is the render's");
    assert!(read("whole.png") == read("merged.png"), "the merged PNG is the render's");

    // Gaps, overlaps, and parts of other renders are refused, naming what differs.
    run(&dir, &["merge", "aov3..7.exr", "-o", "x.exr"]).expect("gap", 1).says("gap", &["samples 0..3 are in no part"]);
    run(&dir, &["merge", "plain0..5.exr", "aov3..7.exr", "-o", "x.exr"])
        .expect("overlap", 1)
        .says("overlap", &["--aovs"]);
    run(&dir, &with(&["render", "-o", "other0..3.exr", "--sample-range", "0..3", "--aovs", "--max-bounces", "2"]))
        .expect("other settings", 0);
    run(&dir, &["merge", "other0..3.exr", "aov3..7.exr", "-o", "x.exr"])
        .expect("other settings", 1)
        .says("other settings", &["different scenes or render settings"]);
    run(&dir, &["merge", "aov0..3.exr", "aov0..3.exr", "aov3..7.exr", "-o", "x.exr"])
        .expect("twice", 1)
        .says("twice", &["both hold samples 0..3"]);
    run(&dir, &["merge", "whole.exr", "-o", "x.exr"])
        .expect("not a part", 1)
        .says("not a part", &["not a part of a render"]);
    run(&dir, &with(&["render", "-o", "x.exr", "--sample-range", "0..3", "--denoise"]))
        .expect("denoise", 1)
        .says("denoise", &["a part cannot take --denoise"]);
    run(&dir, &with(&["render", "-o", "x.exr", "--sample-range", "0..3", "--noise-threshold", "0.05"]))
        .expect("adaptive", 1)
        .says("adaptive", &["--noise-threshold 0"]);

    // Another seed, another build, another format: each said by name.
    let (header, sums) = part::read_part(&dir.join("aov0..3.exr")).unwrap_or_else(|e| panic!("{e:#}"));
    let image = sums.image(3, true);
    let rewrite = |name: &str, header: PartHeader| {
        part::write_part(&dir.join(name), &header, &sums, &image).unwrap_or_else(|e| panic!("{e:#}"));
        run(&dir, &["merge", name, "aov3..7.exr", "-o", "x.exr"]).expect(name, 1).stderr.clone()
    };
    assert!(rewrite("seed.exr", PartHeader { seed: 4, ..header.clone() }).contains("has seed 4"));
    let build = rewrite("build.exr", PartHeader { build: "rt 0.0.1 0000".into(), ..header.clone() });
    assert!(build.contains("render every part with one build of rt"), "{build}");
    let format = rewrite("format.exr", PartHeader { format: 99, ..header.clone() });
    assert!(format.contains("a part of format 99"), "{format}");
}

#[test]
fn exact_sums_beyond_one_binding_fall_back_to_the_means_and_refuse_parts() {
    // 256×256 with AOVs: 17 MiB of exact sums, over this device's 16 MiB per binding.
    let small = rt::gpu::GpuContext::with_binding_limit(std::env::var("RT_ADAPTER").ok().as_deref(), 16 << 20)
        .unwrap_or_else(|e| panic!("{e:#}"));
    let refused = rt::render::check_exact_sums(&small, 256, 256, true).expect_err("over the binding");
    assert!(refused.to_string().contains("exact sums need 17 MiB"), "{refused}");
    assert!(rt::render::check_exact_sums(&small, 256, 256, false).is_ok(), "without AOVs they fit");
    let scene = rt::scene::default_scene().unwrap_or_else(|e| panic!("{e:#}"));
    let mut session = Session::open(&small, scene, BuildQuality::Medium).unwrap_or_else(|e| panic!("{e:#}"));
    let request = RenderRequest {
        width: 256,
        height: 256,
        spp: 1,
        aovs: true,
        exact_sums: true,
        noise_threshold: 0.0,
        ..RenderRequest::from_scene(session.scene())
    };
    let (image, _) = session.render(&request, None).unwrap_or_else(|e| panic!("{e:#}"));
    assert!(session.exact_sums().unwrap_or_else(|e| panic!("{e:#}")).is_none(), "no exact sums kept");
    assert!(image.pixels.iter().any(|p| p[0] > 0.0), "the image comes from the running means");
}
