//! Meshes compiled into the binary, so the built-in default scene renders with no
//! files beside the executable.

use std::path::Path;

/// Asset paths under this prefix name embedded files instead of files on disk.
pub const BUILTIN_PREFIX: &str = "<built-in>";

/// Embedded files, by their path under `assets/` (and under [`BUILTIN_PREFIX`]).
const FILES: &[(&str, &[u8])] = &[(
    "bunny/bunny.obj",
    include_bytes!("../../assets/bunny/bunny.obj"),
)];

/// The contents of a built-in asset such as `<built-in>/bunny/bunny.obj`, or `None`
/// if `path` does not name one.
pub fn lookup(path: &Path) -> Option<&'static [u8]> {
    let rest = path.strip_prefix(BUILTIN_PREFIX).ok()?;
    FILES
        .iter()
        .find(|(name, _)| Path::new(name) == rest)
        .map(|&(_, bytes)| bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::asset::load_mesh;

    #[test]
    fn builtin_lookup_needs_the_prefix() {
        assert!(lookup(Path::new("<built-in>/bunny/bunny.obj")).is_some());
        assert!(lookup(Path::new("bunny/bunny.obj")).is_none());
        assert!(lookup(Path::new("<built-in>/bunny/missing.obj")).is_none());
    }

    #[test]
    fn builtin_bunny_loads_normalised() {
        let mesh = load_mesh(Path::new("<built-in>/bunny/bunny.obj")).expect("bunny loads");
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
