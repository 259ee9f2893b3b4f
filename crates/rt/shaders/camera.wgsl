// The camera's rays, as Cycles makes them: pixel (0, 0) is the top left; a point of
// the image plane (lens shift included) gives a direction from the camera's centre
// (perspective) or a start on the camera's plane (orthographic). With depth of field
// the ray starts on the aperture instead and passes through the point where the
// pinhole ray meets the plane in focus. Rays start at the near clip plane and end at
// the far one. A panoramic camera's rays go where its panorama maps the image
// (`panorama_ray`).

//#include "constants.wgsl"
//#include "common.wgsl"
//#include "rng.wgsl"
//#if panorama
//#include "panorama.wgsl"
//#endif
//#if motion
//#include "motion.wgsl"
//#endif

// Where the camera is and how it is turned at the sample's time.
struct CameraFrame {
    position: vec3f,
    right: vec3f,
    up: vec3f,
    forward: vec3f,
}

fn camera_frame() -> CameraFrame {
    //#if camera_motion
    if frame.camera_motion_steps > 0u {
        let m = camera_motion_now();
        return CameraFrame(
            vec3f(m[0].w, m[1].w, m[2].w),
            vec3f(m[0].x, m[1].x, m[2].x),
            vec3f(m[0].y, m[1].y, m[2].y),
            vec3f(m[0].z, m[1].z, m[2].z),
        );
    }
    //#endif
    return CameraFrame(frame.camera_position, frame.camera_right, frame.camera_up, frame.camera_forward);
}

struct CameraRay {
    origin: vec3f,
    direction: vec3f,
    // Where the ray ends: the far clip plane (INFINITY without one).
    t_max: f32,
}

//#if panorama
// No ray: a direction of zero (outside a fisheye's image).
fn no_camera_ray(ray: CameraRay) -> bool {
    return all(ray.direction == vec3f(0.0));
}
//#endif

fn camera_ray(pixel: vec2u, rng: ptr<function, Rng>) -> CameraRay {
    let jitter = rng_next2(rng);
    let ndc = (vec2f(pixel) + jitter) / vec2f(f32(frame.width), f32(frame.height)) * 2.0 - 1.0;
    let plane = vec2f(ndc.x, -ndc.y) * frame.view_half_extent + frame.view_shift;
    //#if panorama
    if frame.panorama != PANORAMA_NONE {
        // The plane is Cycles' screen about its centre.
        return panorama_ray(plane + 0.5, rng);
    }
    //#endif
    // In the camera's frame: x right, y up, z along the view.
    var origin = vec3f(0.0);
    var direction = vec3f(plane, 1.0);
    // Cycles clips at planes along the view: the pinhole ray's 1/cos to the view
    // turns plane distances into distances along any ray of this pixel (1 for parallel rays).
    let clip_scale = select(length(direction), 1.0, frame.orthographic != 0u);
    if frame.orthographic != 0u {
        origin = vec3f(plane, 0.0);
        direction = vec3f(0.0, 0.0, 1.0);
    }
    //#if depth_of_field
    let lens = sample_aperture(rng_next2(rng)) * frame.aperture_radius;
    // direction.z is 1: the plane in focus is reached at t = focus_distance.
    let focus = origin + direction * frame.focus_distance;
    origin += vec3f(lens, 0.0);
    direction = focus - origin;
    //#endif
    let c = camera_frame();
    let world_origin = c.position + origin.x * c.right + origin.y * c.up + origin.z * c.forward;
    let world_direction = direction.x * c.right + direction.y * c.up + direction.z * c.forward;
    let unit = normalize(world_direction);
    let clip_length = frame.clip_end - frame.clip_start;
    // No far plane (clip_end = INFINITY), or one beyond f32's range: INFINITY, as for other rays.
    let t_max = min(clip_length * clip_scale, INFINITY);
    return CameraRay(world_origin + unit * (frame.clip_start * clip_scale), unit, t_max);
}

//#if panorama
// Cycles' `camera_sample_panorama`: from the camera's centre along the panorama's
// direction; with depth of field, from a point of the aperture set across that
// direction towards where it meets the sphere in focus. Clipped at spheres about the
// camera: clip_start and clip_end are distances along the ray.
fn panorama_ray(uv: vec2f, rng: ptr<function, Rng>) -> CameraRay {
    var direction = panorama_direction(uv);
    let c = camera_frame();
    if all(direction == vec3f(0.0)) {
        return CameraRay(c.position, vec3f(0.0), 0.0);
    }
    var origin = vec3f(0.0);
    //#if depth_of_field
    // In Cycles' panoramic camera space, where x is the view.
    let lens = sample_aperture(rng_next2(rng)) * frame.aperture_radius;
    if frame.aperture_radius > 0.0 {
        let toward = normalize(direction);
        // Cycles' axes across the ray: u towards the view, v = toward × u (any pair
        // along the view itself, where Cycles' u is undefined).
        let along_view = vec3f(1.0, 0.0, 0.0) - toward.x * toward;
        let u = select(vec3f(0.0, 1.0, 0.0), normalize(along_view), dot(along_view, along_view) > 1e-12);
        let v = normalize(cross(toward, u));
        origin = u * lens.x + v * lens.y;
        direction = toward * frame.focus_distance - origin;
    }
    //#endif
    let o = panorama_to_camera(origin);
    let d = panorama_to_camera(direction);
    let world_origin = c.position + o.x * c.right + o.y * c.up + o.z * c.forward;
    let unit = normalize(d.x * c.right + d.y * c.up + d.z * c.forward);
    let t_max = min(frame.clip_end - frame.clip_start, INFINITY);
    return CameraRay(world_origin + unit * frame.clip_start, unit, t_max);
}
//#endif

//#if depth_of_field
// A point of the unit aperture (Cycles' `camera_sample_aperture`): the disk by the
// concentric map, or a regular polygon inscribed in it, one triangle per side, whose
// corners lie at blade_rotation + (2k + 1)π / blades; then squeezed for anamorphic bokeh.
fn sample_aperture(u: vec2f) -> vec2f {
    var p: vec2f;
    if frame.aperture_blades == 0u {
        p = concentric_disk(u);
    } else {
        let corners = f32(frame.aperture_blades);
        let corner = min(floor(u.x * corners), corners - 1.0);
        let s = sqrt(u.x * corners - corner);
        let a = 1.0 - s;
        let b = u.y * s;
        let half_angle = PI / corners;
        let q = vec2f((a + b) * cos(half_angle), (a - b) * sin(half_angle));
        let rotation = frame.blade_rotation + corner * 2.0 * half_angle;
        let c = cos(rotation);
        let r = sin(rotation);
        p = vec2f(c * q.x - r * q.y, r * q.x + c * q.y);
    }
    return vec2f(p.x * frame.inv_aperture_ratio, p.y);
}

// Shirley and Chiu's concentric map of the unit square onto the unit disk.
fn concentric_disk(u: vec2f) -> vec2f {
    let a = 2.0 * u - 1.0;
    if all(a == vec2f(0.0)) {
        return vec2f(0.0);
    }
    if a.x * a.x > a.y * a.y {
        let phi = 0.25 * PI * (a.y / a.x);
        return a.x * vec2f(cos(phi), sin(phi));
    }
    let phi = 0.5 * PI - 0.25 * PI * (a.x / a.y);
    return a.y * vec2f(cos(phi), sin(phi));
}
//#endif
