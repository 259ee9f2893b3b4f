//! The commands a client of `rt watch --stream` sends, one per line, and their parsing.
//! A line that does not parse is refused with a message that says what is wrong; it
//! changes nothing.

use super::view::{Aperture, Lens, Optics, camera_from_view};
use glam::{Mat4, Vec2};
use rt::scene::{Camera, SensorFit, did_you_mean};
use std::path::PathBuf;

/// The longest image side a `size` command may ask for (the GPU may refuse less).
const MAX_SIDE: u32 = 16384;

#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Look through this camera from now on.
    Camera(Camera),
    /// Render `width`×`height` pixels from now on.
    Size { width: u32, height: u32 },
    /// Read the scene again: these files changed (none given: any may have).
    Reload(Vec<PathBuf>),
    /// Refine each state to this many samples per pixel.
    Spp(u32),
    /// Stop rt.
    Quit,
}

const COMMANDS: [&str; 5] = ["camera", "size", "reload", "spp", "quit"];
const CAMERA_KEYS: [&str; 13] = [
    "view",
    "lens",
    "fov",
    "ortho",
    "projection",
    "sensor",
    "fit",
    "shift",
    "aperture",
    "focus",
    "blades",
    "blade_rotation",
    "aperture_ratio",
];
/// The keys that shape the aperture, which need `aperture=`.
const APERTURE_KEYS: [&str; 4] = ["focus", "blades", "blade_rotation", "aperture_ratio"];

/// One line of the protocol; `None` for a blank line or a `#` comment.
pub fn parse(line: &str) -> Option<Result<Command, String>> {
    let line = line.trim();
    if line.is_empty() || line.starts_with('#') {
        return None;
    }
    let (name, rest) = line.split_once(char::is_whitespace).unwrap_or((line, ""));
    let args: Vec<&str> = rest.split_whitespace().collect();
    Some(match name {
        "camera" => camera(&args).map(Command::Camera),
        "size" => size(&args),
        "reload" => Ok(Command::Reload(args.iter().map(PathBuf::from).collect())),
        "spp" => match args[..] {
            [n] => number::<u32>(n, "spp").and_then(|n| positive(n, "spp")).map(Command::Spp),
            _ => Err("spp takes one number: `spp 64`".into()),
        },
        "quit" if args.is_empty() => Ok(Command::Quit),
        "quit" => Err("quit takes no arguments".into()),
        other => Err(format!("unknown command `{other}`{}", did_you_mean(other, COMMANDS.into_iter()))),
    })
}

fn number<T: std::str::FromStr>(text: &str, what: &str) -> Result<T, String> {
    text.parse().map_err(|_| format!("{what}: `{text}` is not a number"))
}

fn positive(n: u32, what: &str) -> Result<u32, String> {
    if n == 0 { Err(format!("{what} must be at least 1")) } else { Ok(n) }
}

fn size(args: &[&str]) -> Result<Command, String> {
    let [w, h] = args[..] else {
        return Err("size takes a width and a height: `size 640 480`".into());
    };
    let (width, height) = (number::<u32>(w, "width")?, number::<u32>(h, "height")?);
    for (side, what) in [(width, "width"), (height, "height")] {
        if side == 0 || side > MAX_SIDE {
            return Err(format!("{what} {side} is not in 1..={MAX_SIDE}"));
        }
    }
    Ok(Command::Size { width, height })
}

/// `n` comma-separated finite numbers.
fn floats(text: &str, n: usize, key: &str) -> Result<Vec<f32>, String> {
    let values: Vec<f32> = text
        .split(',')
        .map(|v| v.trim().parse::<f32>().ok().filter(|v| v.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("{key}: `{text}` is not {n} comma-separated finite numbers"))?;
    if values.len() != n {
        return Err(format!("{key}: {} numbers, expected {n}", values.len()));
    }
    Ok(values)
}

/// A 4×4 matrix written row by row.
fn matrix(text: &str, key: &str) -> Result<Mat4, String> {
    let rows = floats(text, 16, key)?;
    Ok(Mat4::from_cols_slice(&rows).transpose())
}

fn positive_float(text: &str, key: &str) -> Result<f32, String> {
    let v = floats(text, 1, key)?[0];
    if v > 0.0 { Ok(v) } else { Err(format!("{key} must be positive, not {v}")) }
}

fn camera(args: &[&str]) -> Result<Camera, String> {
    let mut parsed = CameraArgs::new();
    for arg in args {
        let Some((key, value)) = arg.split_once('=') else {
            return Err(format!("camera: `{arg}` is not key=value"));
        };
        parsed.set(key, value)?;
    }
    parsed.camera()
}

/// A camera command's keys as read so far.
struct CameraArgs {
    view: Option<Mat4>,
    lens: Option<Lens>,
    optics: Optics,
    radius: Option<f32>,
    aperture: Aperture,
    aperture_keys: Vec<String>,
}

impl CameraArgs {
    fn new() -> Self {
        CameraArgs {
            view: None,
            lens: None,
            optics: Optics::default(),
            radius: None,
            aperture: Aperture { radius: 0.0, focus_distance: 0.0, blades: 0, blade_rotation_deg: 0.0, ratio: 1.0 },
            aperture_keys: Vec::new(),
        }
    }

    fn set(&mut self, key: &str, value: &str) -> Result<(), String> {
        if APERTURE_KEYS.contains(&key) {
            self.aperture_keys.push(key.to_owned());
        }
        if let Some(lens) = lens(key, value)? {
            if self.lens.is_some() {
                return Err("camera: give one of lens=, fov=, ortho=, projection=".into());
            }
            self.lens = Some(lens);
            return Ok(());
        }
        match key {
            "view" => self.view = Some(matrix(value, key)?),
            "sensor" => {
                let s = floats(value, 2, key)?;
                if s.iter().any(|&v| v <= 0.0) {
                    return Err(format!("sensor must be positive, not {value}"));
                }
                self.optics.sensor = Vec2::new(s[0], s[1]);
            }
            "fit" => {
                self.optics.fit = match value {
                    "auto" => SensorFit::Auto,
                    "horizontal" => SensorFit::Horizontal,
                    "vertical" => SensorFit::Vertical,
                    _ => return Err(format!("fit: `{value}` is not auto, horizontal or vertical")),
                };
            }
            "shift" => {
                let s = floats(value, 2, key)?;
                self.optics.shift = Vec2::new(s[0], s[1]);
            }
            "aperture" => self.radius = Some(positive_float(value, key)?),
            "focus" => self.aperture.focus_distance = positive_float(value, key)?,
            "blades" => self.aperture.blades = number(value, key)?,
            "blade_rotation" => self.aperture.blade_rotation_deg = floats(value, 1, key)?[0],
            "aperture_ratio" => self.aperture.ratio = positive_float(value, key)?,
            _ => return Err(format!("camera: unknown key `{key}`{}", did_you_mean(key, CAMERA_KEYS.into_iter()))),
        }
        Ok(())
    }

    fn camera(self) -> Result<Camera, String> {
        let view = self.view.ok_or("camera needs view=<16 numbers, the world-to-camera matrix row by row>")?;
        let mut optics = self.optics;
        optics.lens = self.lens.unwrap_or(optics.lens);
        optics.aperture = match self.radius {
            Some(radius) if self.aperture.focus_distance > 0.0 => Some(Aperture { radius, ..self.aperture }),
            Some(_) => return Err("camera: aperture= needs focus=<metres to the plane in focus>".into()),
            None => match self.aperture_keys.first() {
                Some(key) => return Err(format!("camera: {key}= only applies with aperture=<radius in metres>")),
                None => None,
            },
        };
        camera_from_view(view, optics)
    }
}

/// The projection `key` sets, if it is one of the lens keys.
fn lens(key: &str, value: &str) -> Result<Option<Lens>, String> {
    Ok(Some(match key {
        "lens" => Lens::FocalLength(positive_float(value, key)?),
        "fov" => {
            let degrees = positive_float(value, key)?;
            if degrees >= 180.0 {
                return Err(format!("fov must be below 180 degrees, not {degrees}"));
            }
            Lens::FovY(degrees)
        }
        "ortho" => Lens::Orthographic(positive_float(value, key)?),
        "projection" => Lens::Matrix(matrix(value, key)?),
        _ => return Ok(None),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;
    use rt::scene::Projection;

    const IDENTITY: &str = "1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1";

    fn error(line: &str) -> String {
        parse(line).expect("a command").expect_err("an error")
    }

    #[test]
    fn commands_parse() {
        assert_eq!(parse("size 64 32"), Some(Ok(Command::Size { width: 64, height: 32 })));
        assert_eq!(parse("  quit "), Some(Ok(Command::Quit)));
        assert_eq!(parse("reload a.toml b.gltf"), Some(Ok(Command::Reload(vec!["a.toml".into(), "b.gltf".into()]))));
        assert_eq!(parse("spp 8"), Some(Ok(Command::Spp(8))));
        assert_eq!(parse("# a comment"), None);
        assert_eq!(parse(""), None);
        let Some(Ok(Command::Camera(c))) = parse(&format!("camera view={IDENTITY} lens=35 sensor=36,24 fit=vertical"))
        else {
            panic!("camera")
        };
        assert_eq!(c.projection, Projection::FocalLength { mm: 35.0 });
        assert_eq!(c.sensor_fit, SensorFit::Vertical);
        assert!((c.look_at - c.position - Vec3::NEG_Z).length() < 1e-6);
        assert_eq!(c.depth_of_field, None);
        let line = format!("camera view={IDENTITY} lens=50 aperture=0.025 focus=4 blades=5 blade_rotation=10");
        let Some(Ok(Command::Camera(c))) = parse(&line) else { panic!("camera with an aperture") };
        let dof = c.depth_of_field.expect("depth of field");
        // 50 mm over twice the f-number is 25 mm: f/1.
        assert!((dof.fstop - 1.0).abs() < 1e-6, "{dof:?}");
        assert_eq!((dof.focus_distance, dof.blades, dof.blade_rotation_deg, dof.aperture_ratio), (4.0, 5, 10.0, 1.0));
    }

    #[test]
    fn bad_lines_say_what_is_wrong() {
        assert_eq!(error("camra view=1"), "unknown command `camra`; did you mean `camera`?");
        assert_eq!(error("size 64"), "size takes a width and a height: `size 640 480`");
        assert_eq!(error("size 0 64"), "width 0 is not in 1..=16384");
        assert_eq!(error("size 64 x"), "height: `x` is not a number");
        assert_eq!(error("spp 0"), "spp must be at least 1");
        assert_eq!(
            error(&format!("camera view={IDENTITY} lense=50")),
            "camera: unknown key `lense`; did you mean `lens`?"
        );
        assert_eq!(error("camera view=1,2,3"), "view: 3 numbers, expected 16");
        assert_eq!(error("camera lens=50"), "camera needs view=<16 numbers, the world-to-camera matrix row by row>");
        assert_eq!(
            error(&format!("camera view={IDENTITY} lens=50 fov=40")),
            "camera: give one of lens=, fov=, ortho=, projection="
        );
        assert_eq!(
            error(&format!("camera view={IDENTITY} aperture=0.01")),
            "camera: aperture= needs focus=<metres to the plane in focus>"
        );
        assert_eq!(
            error(&format!("camera view={IDENTITY} focus=3")),
            "camera: focus= only applies with aperture=<radius in metres>"
        );
        assert_eq!(error(&format!("camera view={IDENTITY} aperture=-1 focus=3")), "aperture must be positive, not -1");
        assert_eq!(
            error(&format!("camera view={IDENTITY} apperture=0.1")),
            "camera: unknown key `apperture`; did you mean `aperture`?"
        );
        assert_eq!(
            error("camera view=1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,nan"),
            "view: `1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,nan` is not 16 comma-separated finite numbers"
        );
    }
}
