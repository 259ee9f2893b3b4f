//! Meshes compiled into the binary, so the built-in default scene renders with no
//! files beside the executable.

use crate::files::input::{InputError, InputProblem};
use crate::scene::BUILTIN_PREFIX;
use std::borrow::Cow;
use std::path::{Component, Path, PathBuf};

/// Embedded files, by their path in the repository (under [`BUILTIN_PREFIX`]).
const FILES: &[(&str, &[u8])] = &[
    ("assets/bunny/bunny.obj", include_bytes!("../../../../assets/bunny/bunny.obj")),
    ("assets/cornell_box/cornell_box.obj", include_bytes!("../../../../assets/cornell_box/cornell_box.obj")),
    ("assets/cornell_box/cornell_box.mtl", include_bytes!("../../../../assets/cornell_box/cornell_box.mtl")),
];

/// The contents of a built-in file such as `<built-in>/assets/bunny/bunny.obj`
/// (`..` resolved, as the built-in scene's relative paths produce), or `None`
/// if `path` does not name one.
pub fn lookup(path: &Path) -> Option<&'static [u8]> {
    let rest = path.strip_prefix(BUILTIN_PREFIX).ok()?;
    let mut parts: Vec<&std::ffi::OsStr> = Vec::new();
    for c in rest.components() {
        match c {
            Component::Normal(p) => parts.push(p),
            Component::ParentDir => {
                parts.pop()?;
            }
            _ => {}
        }
    }
    let wanted: PathBuf = parts.iter().collect();
    FILES.iter().find(|(name, _)| Path::new(name) == wanted).map(|&(_, bytes)| bytes)
}

/// Reads a file from disk (a regular file only, see [`crate::files::input`]), or from
/// the binary for a built-in path.
pub fn read(path: &Path) -> Result<Cow<'static, [u8]>, InputError> {
    if path.starts_with(BUILTIN_PREFIX) {
        return lookup(path).map(Cow::Borrowed).ok_or_else(|| InputError {
            path: path.to_path_buf(),
            problem: InputProblem::Io(std::io::Error::new(std::io::ErrorKind::NotFound, "no such built-in file")),
        });
    }
    crate::files::read(path).map(Cow::Owned)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asset::load_mesh;

    #[test]
    fn builtin_lookup_needs_the_prefix() {
        assert!(lookup(Path::new("<built-in>/scenes/../assets/bunny/bunny.obj")).is_some());
        assert!(lookup(Path::new("assets/bunny/bunny.obj")).is_none());
        assert!(lookup(Path::new("<built-in>/assets/bunny/missing.obj")).is_none());
    }

    #[test]
    fn builtin_bunny_loads_normalised() {
        let mesh = load_mesh(Path::new("<built-in>/assets/bunny/bunny.obj")).expect("bunny loads");
        assert_eq!(mesh.indices.len(), 3674);
        assert_eq!(mesh.positions.len(), 1839);
        assert_eq!(mesh.normals.as_ref().map(Vec::len), Some(1839));
        assert_eq!(mesh.materials.len(), 1);
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in &mesh.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        assert_eq!(lo[1], 0.0);
        assert_eq!(hi[1], 1.0);
        // The bottom of the bounding box is centred on the origin.
        assert!((lo[0] + hi[0]).abs() < 1e-5 && (lo[2] + hi[2]).abs() < 1e-5);
    }
}
