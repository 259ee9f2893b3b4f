// Pinhole camera with a vertical field of view; pixel (0, 0) is the top left.

//#include "common.wgsl"

fn camera_ray_direction(pixel: vec2u, jitter: vec2f) -> vec3f {
    let ndc = (vec2f(pixel) + jitter) / vec2f(f32(frame.width), f32(frame.height)) * 2.0 - 1.0;
    let x = ndc.x * frame.tan_half_fov_y * frame.aspect;
    let y = -ndc.y * frame.tan_half_fov_y;
    return normalize(frame.camera_forward + x * frame.camera_right + y * frame.camera_up);
}
