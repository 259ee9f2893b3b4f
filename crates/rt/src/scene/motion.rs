//! Motion over the shutter, as Cycles blurs it: an object's (or the camera's) transforms
//! at evenly spaced times from the shutter's opening to its closing, each split into a
//! translation, a rotation and the rest (scale and shear), interpolated piecewise between
//! neighbouring keys (the rotation along the shorter arc, the rest linearly) and composed
//! again. A sample's time is uniform over the open shutter.

use super::parse::{Seg, Source};
use super::validate::matrix_of;
use super::{Camera, SceneError};
use glam::{DMat3, DMat4, DQuat, DVec3, Mat4, Vec3};

/// The most keys one motion may have: Blender's largest Motion Steps (7) gives 2⁶·2 + 1.
pub const MAX_MOTION_KEYS: usize = 129;
/// An object's motion as the GPU follows it: world-to-object matrices at this many times
/// per interval between keys (at most [`MAX_MOTION_SAMPLES`] in all), computed here from
/// the decomposed keys and interpolated linearly there (see [`Motion::world_to_object_samples`]).
pub const MOTION_SAMPLES_PER_INTERVAL: usize = 128;
/// The most samples one object's motion has (its count travels in 8 bits).
pub const MAX_MOTION_SAMPLES: usize = 255;
/// The most keys the camera's motion may have (they travel with the frame's constants):
/// Blender's Motion Steps up to 4.
pub const MAX_CAMERA_MOTION_KEYS: usize = 17;

/// A transform split as it is interpolated: `translation · rotation · stretch`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Decomposed {
    pub translation: DVec3,
    /// A unit quaternion, on the same side of the sphere as the key before it.
    pub rotation: DQuat,
    /// Scale, shear and any reflection: the rotation's inverse times the linear part.
    pub stretch: DMat3,
}

/// Transforms at evenly spaced times over the open shutter (at least two), split for
/// interpolation once, when the motion is made.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    keys: Vec<Mat4>,
    decomposed: Vec<Decomposed>,
}

impl Motion {
    pub fn new(keys: Vec<Mat4>) -> Self {
        let decomposed = decompose_keys(&keys);
        Self { keys, decomposed }
    }

    pub fn keys(&self) -> &[Mat4] {
        &self.keys
    }

    /// The keys split for interpolation, each rotation on the side of its predecessor's.
    pub fn decomposed(&self) -> &[Decomposed] {
        &self.decomposed
    }

    /// The world-to-object matrices at evenly spaced times from the shutter's opening to
    /// its closing, dense enough that interpolating neighbours linearly (what the GPU does
    /// where a ray meets the object: a lerp, no slerp and no inverse in the traversal)
    /// stays within a few 10⁻⁴ of the object's size of the decomposed motion, for turns up to a
    /// full one between the keys of a three-key motion:
    /// between samples δ apart a rotation's chord shortens by 1 − cos(δ/2).
    pub fn world_to_object_samples(&self) -> Vec<DMat4> {
        let keys = &self.decomposed;
        let count = (1 + MOTION_SAMPLES_PER_INTERVAL * (keys.len() - 1)).min(MAX_MOTION_SAMPLES);
        (0..count).map(|i| interpolate(keys, i as f64 / (count - 1) as f64).inverse()).collect()
    }

    /// The box that holds `lo..hi` transformed at every time of the shutter: the boxes at
    /// 64 times per interval between keys, grown by the farthest any corner moves between
    /// two of those times (the motion of a point of the box is affine in the point, so a
    /// corner moves farthest; between two times a point stays within that of both).
    pub fn swept_box(&self, lo: Vec3, hi: Vec3) -> (Vec3, Vec3) {
        const PER_INTERVAL: usize = 64;
        let keys = &self.decomposed;
        let steps = PER_INTERVAL * (keys.len() - 1);
        let corners: Vec<DVec3> = (0..8)
            .map(|i| {
                let pick = |bit: usize, l: f32, h: f32| f64::from(if i & bit == 0 { l } else { h });
                DVec3::new(pick(1, lo.x, hi.x), pick(2, lo.y, hi.y), pick(4, lo.z, hi.z))
            })
            .collect();
        let (mut min, mut max) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        let mut reach = 0.0f64;
        let mut before: Option<Vec<DVec3>> = None;
        for s in 0..=steps {
            let m = interpolate(keys, s as f64 / steps as f64);
            let placed: Vec<DVec3> = corners.iter().map(|c| m.transform_point3(*c)).collect();
            for p in &placed {
                min = min.min(*p);
                max = max.max(*p);
            }
            if let Some(before) = &before {
                reach = placed.iter().zip(before).map(|(a, b)| a.distance(*b)).fold(reach, f64::max);
            }
            before = Some(placed);
        }
        ((min - reach).as_vec3(), (max + reach).as_vec3())
    }
}

/// `keys` split for interpolation, each rotation on the side of its predecessor's (a
/// quaternion and its negation are one rotation; interpolating between opposite ones
/// would take the long way round).
fn decompose_keys(keys: &[Mat4]) -> Vec<Decomposed> {
    let mut out: Vec<Decomposed> = Vec::with_capacity(keys.len());
    for key in keys {
        let mut d = decompose(&key.as_dmat4());
        if let Some(before) = out.last()
            && before.rotation.dot(d.rotation) < 0.0
        {
            d.rotation = -d.rotation;
        }
        out.push(d);
    }
    out
}

/// `m` split by its polar decomposition (Higham's iteration R ← (R + R⁻ᵀ)/2, which
/// converges to the rotation nearest the linear part; a reflection is left to the stretch).
pub fn decompose(m: &DMat4) -> Decomposed {
    let linear = DMat3::from_mat4(*m);
    let mut r = linear;
    for _ in 0..100 {
        let next = (r + r.inverse().transpose()) * 0.5;
        let change = (0..3).map(|c| (next.col(c) - r.col(c)).abs().element_sum()).fold(0.0, f64::max);
        r = next;
        if change <= 1e-12 {
            break;
        }
    }
    if r.determinant() < 0.0 {
        r = -r;
    }
    let rotation = DQuat::from_mat3(&r).normalize();
    let stretch = DMat3::from_quat(rotation).transpose() * linear;
    Decomposed { translation: m.w_axis.truncate(), rotation, stretch }
}

/// The transform at `t` in [0, 1] over the shutter: between the two keys about it, the
/// rotation slerped (normalised linear interpolation where they nearly agree, as Cycles),
/// translation and stretch linearly.
pub fn interpolate(keys: &[Decomposed], t: f64) -> DMat4 {
    let last = keys.len() - 1;
    let scaled = t.clamp(0.0, 1.0) * last as f64;
    let step = (scaled as usize).min(last - 1);
    let f = scaled - step as f64;
    let (a, b) = (&keys[step], &keys[step + 1]);
    let rotation = slerp(a.rotation, b.rotation, f);
    let linear = DMat3::from_quat(rotation) * (a.stretch * (1.0 - f) + b.stretch * f);
    DMat4::from_mat3_translation(linear, a.translation.lerp(b.translation, f))
}

/// Cycles' `quat_interpolate` (the quaternions already on one side).
fn slerp(a: DQuat, b: DQuat, t: f64) -> DQuat {
    let cos = a.dot(b);
    if cos > 0.9995 {
        return (a * (1.0 - t) + b * t).normalize();
    }
    let theta = cos.clamp(-1.0, 1.0).acos();
    let perpendicular = (b - a * cos).normalize();
    a * (theta * t).cos() + perpendicular * (theta * t).sin()
}

/// A `motion` key of a `[[mesh]]`: its list of row-major matrices, each as `matrix` is.
pub(super) fn validate_keys(src: &Source, p: &[Seg], keys: &[[f32; 16]]) -> Result<Motion, SceneError> {
    check_count(src, p, keys.len(), MAX_MOTION_KEYS)?;
    let keys = keys.iter().map(|k| matrix_of(src, p, "motion", k)).collect::<Result<_, _>>()?;
    Ok(Motion::new(keys))
}

/// `[camera] motion`: the camera's position, look_at and up at each key, as its own keys
/// are given; each becomes the matrix whose columns are its right, up and forward
/// directions and its position.
pub(super) fn validate_camera(src: &Source, poses: &[super::schema::CameraPose]) -> Result<Motion, SceneError> {
    let p = [Seg::Key("camera")];
    check_count(src, &p, poses.len(), MAX_CAMERA_MOTION_KEYS)?;
    let mut keys = Vec::with_capacity(poses.len());
    for (i, pose) in poses.iter().enumerate() {
        let values = [pose.position, pose.look_at, pose.up.unwrap_or([0.0, 1.0, 0.0])].concat();
        src.finite(&p, "motion", &values)?;
        let camera = Camera {
            position: pose.position.into(),
            look_at: pose.look_at.into(),
            up: pose.up.map(Vec3::from),
            ..Camera::default()
        };
        if camera.position == camera.look_at {
            return Err(src.error(&p, "motion", format!("key {}: look_at must differ from position", i + 1)));
        }
        let (right, up, forward) = camera.basis();
        if !(right.is_finite() && up.is_finite()) {
            return Err(src.error(&p, "motion", format!("key {}: up must not lie along the view", i + 1)));
        }
        keys.push(Mat4::from_cols(right.extend(0.0), up.extend(0.0), forward.extend(0.0), camera.position.extend(1.0)));
    }
    Ok(Motion::new(keys))
}

fn check_count(src: &Source, p: &[Seg], count: usize, most: usize) -> Result<(), SceneError> {
    if !(2..=most).contains(&count) {
        return Err(src.error(
            p,
            "motion",
            format!("must list 2 to {most} keys (the shutter's opening to its closing), got {count}"),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DMat4, b: DMat4) -> bool {
        a.abs_diff_eq(b, 1e-6)
    }

    #[test]
    fn a_decomposed_key_composes_back() {
        let shear =
            DMat4::from_cols_array(&[1.0, 0.3, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, -0.5, 0.0, 0.0, 0.0, 0.0, 1.0]);
        let m = DMat4::from_translation(DVec3::new(1.0, -2.0, 3.0)) * DMat4::from_rotation_y(0.7) * shear;
        let d = decompose(&m);
        assert!((d.rotation.length() - 1.0).abs() < 1e-12);
        assert!(close(interpolate(&[d, d], 0.37), m));
    }

    #[test]
    fn a_spin_is_interpolated_along_its_arc() {
        let motion = Motion::new(vec![Mat4::IDENTITY, Mat4::from_rotation_z(1.5), Mat4::from_rotation_z(3.0)]);
        let keys = motion.decomposed();
        let halfway = interpolate(keys, 0.25);
        assert!(close(halfway, DMat4::from_rotation_z(f64::from(1.5f32) * 0.5)), "{halfway:?}");
        // The box of a unit square turning by 3 rad about its corner holds the whole sweep.
        let (lo, hi) = motion.swept_box(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0));
        for i in 0..=300 {
            let m = interpolate(keys, f64::from(i) / 300.0);
            for c in [DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.7, 0.2, 0.0)] {
                let p = m.transform_point3(c).as_vec3();
                assert!(p.cmpge(lo).all() && p.cmple(hi).all(), "{p} outside {lo}..{hi}");
            }
        }
    }

    #[test]
    fn the_gpus_samples_follow_the_decomposed_motion() {
        let turn = Mat4::from_translation(Vec3::new(1.0, 0.0, 0.0)) * Mat4::from_rotation_y(3.0);
        let motion = Motion::new(vec![Mat4::IDENTITY, turn, Mat4::from_scale(Vec3::splat(2.0))]);
        let samples = motion.world_to_object_samples();
        assert_eq!(samples.len(), 1 + 2 * MOTION_SAMPLES_PER_INTERVAL.min(127));
        let keys = motion.decomposed();
        let (lo, hi) = motion.swept_box(Vec3::splat(-1.0), Vec3::splat(1.0));
        for i in 0..=997 {
            let t = f64::from(i) / 997.0;
            let x = t * (samples.len() - 1) as f64;
            let k = (x as usize).min(samples.len() - 2);
            let f = x - k as f64;
            let lerped = samples[k] * (1.0 - f) + samples[k + 1] * f;
            let exact = interpolate(keys, t);
            for p in [DVec3::new(1.0, 1.0, 1.0), DVec3::new(-1.0, 0.5, 1.0)] {
                let gpu = lerped.inverse().transform_point3(p);
                assert!(
                    gpu.distance(exact.transform_point3(p)) < 1e-3,
                    "t {t}: {gpu} vs {}",
                    exact.transform_point3(p)
                );
                let g = gpu.as_vec3();
                assert!(g.cmpge(lo).all() && g.cmple(hi).all(), "t {t}: {g} outside {lo}..{hi}");
            }
        }
    }

    #[test]
    fn opposite_quaternions_turn_the_short_way() {
        let motion = Motion::new(vec![Mat4::from_rotation_x(3.0), Mat4::from_rotation_x(-3.0)]);
        let keys = motion.decomposed();
        // 3 rad to −3 rad is 0.28 rad through π, not 6 rad back through 0.
        let middle = interpolate(keys, 0.5);
        assert!(close(middle, DMat4::from_rotation_x(std::f64::consts::PI)), "{middle:?}");
    }
}
