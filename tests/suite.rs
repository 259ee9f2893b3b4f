//! Every integration test, in one binary: one link and one GPU device for them all,
//! instead of one ~90 MB executable per file. Each module is the file of its name.
//! One file's tests run alone with `cargo test --release --test suite NAME::`.

mod atmosphere;
mod common;
mod watch_harness;

mod adaptive;
mod aovs;
mod asset_cache;
mod atmosphere_accuracy;
mod atmosphere_energy;
mod atmosphere_robustness;
mod atmosphere_tables;
mod bad_input;
mod bench_accuracy;
mod bench_compare;
mod blender_engine;
mod blender_environment;
mod blender_live;
mod blender_live_watch;
mod blender_roundtrip;
mod camera_lens;
mod cycles_camera;
mod cycles_environment;
mod cycles_instances;
mod cycles_lamps;
mod cycles_normal_maps;
mod cycles_principled;
mod cycles_textures;
mod denoise;
mod environment;
mod furnace;
mod fuzz_inputs;
mod geometry_precision;
mod instances;
mod lamps;
mod light_tree;
mod materials;
mod mitsuba_validation;
mod normal_maps;
mod readme_defaults;
mod robust_first_hour;
mod robust_gpu_errors;
mod robust_gpu_limits;
mod robust_outputs;
mod robust_silent;
mod robust_watch;
mod sample_lanes;
mod scale_export;
mod scenes_render;
mod sentinel;
mod texture_inputs;
mod textures;
mod trace_reference;
mod watch;
mod watch_stream;
