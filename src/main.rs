//! The `rt` command line: parses arguments, calls the library, maps errors to exit codes:
//! 0 success, 1 a bad input or a failed render, 2 a usage error (clap's), 3 a render that
//! `--strict` found dropping samples or rays.

use anyhow::Result;
use clap::Parser;
use rt::render::{Progress, json_event};
use rt::scene::{self, Scene};
use std::path::Path;
use std::process::ExitCode;

mod cli;
use cli::args::{Cli, Command};
use cli::commands::{bench, pack, watch};
use cli::render::{StrictFinding, merge, render};

/// The exit status of a render that `--strict` rejects.
pub(crate) const EXIT_STRICT: u8 = 3;

pub(crate) fn load_scene(path: Option<&Path>) -> Result<Scene> {
    Ok(match path {
        Some(p) => scene::load(p)?,
        None => scene::default_scene()?,
    })
}

/// Logs through env_logger (warnings by default); with `--progress json`, as JSON events.
fn init_logging(json: bool) {
    let mut logger = env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn"));
    if json {
        logger.format(|out, record| {
            use std::io::Write;
            writeln!(out, "{}", json_event("warning", serde_json::json!({ "message": record.args().to_string() })))
        });
    }
    logger.init();
}

fn main() -> ExitCode {
    rt::gpu::ensure_runtime_dir();
    rt::progress::set_meters(&cli::meters::TerminalBars);
    let cli = Cli::parse();
    let json = matches!(&cli.command, Command::Render(args) if args.progress == Progress::Json);
    init_logging(json);
    let adapter = cli.adapter.as_deref();
    let result = match cli.command {
        Command::Pack { paths, quality, force } => pack(&paths, quality, force),
        Command::Render(args) => render(args, adapter),
        Command::Merge { parts, output } => merge(&parts, &output),
        Command::Watch(args) => watch(args, adapter),
        Command::Info { scene, quality, inputs: true } => rt::info::print_inputs(scene.as_deref(), quality),
        Command::Info { scene, quality, inputs: false } => {
            load_scene(scene.as_deref()).and_then(|s| rt::info::print_info(s, quality, adapter))
        }
        Command::Doctor => {
            rt::doctor::findings(rt::VERSION, adapter).iter().for_each(|f| println!("{f}"));
            Ok(())
        }
        Command::Bench(command) => bench(command, adapter),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            match json {
                true => eprintln!("{}", json_event("error", serde_json::json!({ "message": format!("{e:#}") }))),
                false => eprintln!("error: {e:#}"),
            }
            if e.is::<StrictFinding>() { ExitCode::from(EXIT_STRICT) } else { ExitCode::FAILURE }
        }
    }
}
