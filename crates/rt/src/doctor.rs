//! `rt doctor`: what rt finds on this machine and what to do about what it does not, one
//! line each: the build, the Vulkan drivers and GPU adapters (and the one rt picks), Open
//! Image Denoise, Blender's Python module for the exporter, and a Blender with rt's
//! extension.

use crate::denoise::{DenoiseDevice, Denoiser};
use std::path::{Path, PathBuf};
use std::process::Command;

/// One finding: what was looked at, what was found, and what to do when it is missing.
pub struct Finding {
    pub what: &'static str,
    pub found: Result<String, String>,
}

impl std::fmt::Display for Finding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.found {
            Ok(found) => write!(f, "ok       {:<16} {found}", self.what),
            Err(help) => write!(f, "missing  {:<16} {help}", self.what),
        }
    }
}

/// Everything `rt doctor` reports, in order; `adapter` is the `--adapter` rt was given.
pub fn findings(version: &str, adapter: Option<&str>) -> Vec<Finding> {
    let build = format!("rt {version}, {}", if cfg!(feature = "denoise") { "with denoise" } else { "without denoise" });
    vec![
        Finding { what: "build", found: Ok(build) },
        Finding { what: "vulkan drivers", found: vulkan_drivers() },
        Finding { what: "gpu adapters", found: adapters() },
        Finding { what: "gpu rt uses", found: picked(adapter) },
        Finding { what: "denoiser", found: denoiser() },
        Finding { what: "bpy", found: bpy() },
        Finding { what: "blender", found: blender() },
    ]
}

/// The Vulkan ICD manifests the loader reads.
fn vulkan_drivers() -> Result<String, String> {
    let mut manifests = Vec::new();
    for var in ["VK_DRIVER_FILES", "VK_ICD_FILENAMES"] {
        if let Some(list) = std::env::var_os(var) {
            manifests.extend(std::env::split_paths(&list).filter(|p| p.is_file()));
        }
    }
    for dir in ["/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d", "/usr/local/share/vulkan/icd.d"] {
        if let Ok(entries) = std::fs::read_dir(dir) {
            manifests
                .extend(entries.flatten().map(|e| e.path()).filter(|p| p.extension().is_some_and(|x| x == "json")));
        }
    }
    let names: Vec<String> =
        manifests.iter().filter_map(|p| p.file_name()).map(|n| n.to_string_lossy().into_owned()).collect();
    if names.is_empty() {
        return Err(
            "no Vulkan driver: install your GPU's, or Mesa's CPU driver: sudo apt-get install mesa-vulkan-drivers"
                .into(),
        );
    }
    Ok(names.join(", "))
}

fn adapters() -> Result<String, String> {
    let names = crate::gpu::adapter_names();
    if names.is_empty() {
        return Err("Vulkan finds no adapter: install a driver (see above)".into());
    }
    Ok(names.join("; "))
}

fn picked(adapter: Option<&str>) -> Result<String, String> {
    crate::gpu::GpuContext::new(adapter).map(|ctx| ctx.describe()).map_err(|e| format!("{e:#}"))
}

fn denoiser() -> Result<String, String> {
    Denoiser::new(DenoiseDevice::Auto)
        .map(|d| format!("Open Image Denoise on {}", d.describe()))
        .map_err(|e| format!("{e:#}"))
}

/// The Python with bpy that the exporter's command line and the tests use.
fn bpy() -> Result<String, String> {
    let python =
        std::env::var_os("RT_BPY_PYTHON").map(PathBuf::from).unwrap_or_else(|| PathBuf::from(".venv-bpy/bin/python"));
    let help = "no Python with Blender's module (bpy) for the exporter's command line: scripts/test makes \
                .venv-bpy (or set RT_BPY_PYTHON); Blender itself runs the exporter too";
    let out = run(&python, &["-c", "import bpy; print(bpy.app.version_string)"]).ok_or(help)?;
    Ok(format!("bpy {out} at {}", python.display()))
}

/// A Blender on PATH (or $BLENDER), and whether rt's extension is installed in it.
fn blender() -> Result<String, String> {
    let blender = std::env::var_os("BLENDER").map(PathBuf::from).unwrap_or_else(|| PathBuf::from("blender"));
    let version = run(&blender, &["--factory-startup", "-b", "--version"])
        .and_then(|out| out.lines().find(|l| l.starts_with("Blender ")).map(str::to_owned))
        .ok_or("no Blender on PATH (or $BLENDER): rt's extension needs Blender 4.2 or later, from blender.org")?;
    let number = version.split_whitespace().nth(1).unwrap_or("");
    let (major, minor) = number.split_once('.').unwrap_or((number, "0"));
    let (major, minor): (u32, u32) = (major.parse().unwrap_or(0), minor.parse().unwrap_or(0));
    if (major, minor) < (4, 2) {
        return Err(format!("{version}: rt's extension needs Blender 4.2 or later"));
    }
    let home = std::env::var_os("HOME").map(PathBuf::from).unwrap_or_default();
    let extension = home.join(format!(".config/blender/{major}.{minor}/extensions/user_default/rt_blender"));
    match extension.is_dir() {
        true => Ok(format!("{version}, rt's extension in {}", extension.display())),
        false => Err(format!(
            "{version} without rt's extension: scripts/package_blender, then drag rt_blender.zip onto Blender"
        )),
    }
}

/// A program's trimmed standard output, if it ran and succeeded.
fn run(program: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new(program).args(args).output().ok().filter(|o| o.status.success())?;
    Some(String::from_utf8_lossy(&out.stdout).trim().to_owned())
}
