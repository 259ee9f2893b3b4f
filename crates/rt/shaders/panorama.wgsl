// Blender's panoramic cameras, mapped as Cycles maps them
// (`intern/cycles/kernel/camera/projection.h`): a point (u, v) of Cycles' screen ([0, 1]²,
// v up, the lens shift added) gives a direction in Cycles' panoramic camera space, x along
// the view, y to the left, z up (the mirror ball's: x right, y back against the view, z
// up); `panorama_to_camera` turns it into rt's camera frame, as Cycles' camera matrix
// (`blender_camera_matrix`) does. `scene::Panorama` is the same on the host.

//#include "common.wgsl"


// Cycles' `panorama_to_direction`, not normalised; zero outside a fisheye's or a mirror
// ball's image, where Cycles sends no ray.
fn panorama_direction(uv: vec2f) -> vec3f {
    switch frame.panorama {
        case PANORAMA_EQUIRECTANGULAR: {
            let range = frame.equirectangular_range;
            let phi = range.x * uv.x + range.y;
            let theta = range.z * uv.y + range.w;
            return vec3f(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
        }
        case PANORAMA_FISHEYE_EQUIDISTANT: {
            let p = (uv - 0.5) * 2.0;
            let r = length(p);
            if r > 1.0 {
                return vec3f(0.0);
            }
            return fisheye_direction(r * frame.fisheye_fov * 0.5, p, r);
        }
        case PANORAMA_FISHEYE_EQUISOLID: {
            let p = (uv - 0.5) * frame.fisheye_sensor;
            let r = length(p);
            if r > 2.0 * frame.fisheye_lens * sin(frame.fisheye_fov * 0.25) {
                return vec3f(0.0);
            }
            return fisheye_direction(2.0 * asin(r / (2.0 * frame.fisheye_lens)), p, r);
        }
        default: {
            // The mirror ball: its normal, facing the camera (−y), reflects the view (+y).
            let x = 2.0 * uv.x - 1.0;
            let z = 2.0 * uv.y - 1.0;
            if x * x + z * z > 1.0 {
                return vec3f(0.0);
            }
            let n = vec3f(x, -sqrt(max(1.0 - x * x - z * z, 0.0)), z);
            let incoming = vec3f(0.0, -1.0, 0.0);
            return 2.0 * dot(n, incoming) * n - incoming;
        }
    }
}

// Cycles' `fisheye_to_direction`: `theta` from the view, turned towards `p` (at radius `r`).
fn fisheye_direction(theta: f32, p: vec2f, r: f32) -> vec3f {
    var phi = acos(clamp(select(0.0, p.x / r, r != 0.0), -1.0, 1.0));
    if p.y < 0.0 {
        phi = -phi;
    }
    return vec3f(cos(theta), -cos(phi) * sin(theta), sin(phi) * sin(theta));
}

// Cycles' panoramic camera space to rt's camera frame (x right, y up, z along the view).
fn panorama_to_camera(d: vec3f) -> vec3f {
    if frame.panorama == PANORAMA_MIRROR_BALL {
        return vec3f(d.x, d.z, -d.y);
    }
    return vec3f(-d.y, d.z, d.x);
}

// rt's camera frame to Cycles' panoramic camera space: `panorama_to_camera` undone.
fn camera_to_panorama(c: vec3f) -> vec3f {
    if frame.panorama == PANORAMA_MIRROR_BALL {
        return vec3f(c.x, -c.z, c.y);
    }
    return vec3f(c.z, -c.x, c.y);
}

// Cycles' `direction_to_panorama`: where unit direction `d` of Cycles' panoramic camera
// space falls on the image, in the screen `panorama_direction` reads (the lens shift
// included); outside a fisheye's circle too.
fn panorama_uv(d: vec3f) -> vec2f {
    switch frame.panorama {
        case PANORAMA_EQUIRECTANGULAR: {
            let range = frame.equirectangular_range;
            if all(d == vec3f(0.0)) {
                return vec2f(0.0);
            }
            return vec2f((atan2(d.y, d.x) - range.y) / range.x, (acos(d.z / length(d)) - range.w) / range.z);
        }
        case PANORAMA_FISHEYE_EQUIDISTANT: {
            let uv = atan2(length(d.yz), d.x) / frame.fisheye_fov * safe_normalize2(d.yz);
            return vec2f(0.5 - uv.x, uv.y + 0.5);
        }
        case PANORAMA_FISHEYE_EQUISOLID: {
            let r = 2.0 * frame.fisheye_lens * sin(acos(clamp(d.x, -1.0, 1.0)) * 0.5);
            let uv = r * safe_normalize2(d.yz);
            return vec2f(0.5 - uv.x / frame.fisheye_sensor.x, uv.y / frame.fisheye_sensor.y + 0.5);
        }
        default: {
            // The mirror ball: the normal halfway between the view (+y) and `d`.
            var h = d - vec3f(0.0, 1.0, 0.0);
            let div = 2.0 * sqrt(max(-0.5 * h.y, 0.0));
            if div > 0.0 {
                h /= div;
            }
            return vec2f(0.5 * (h.x + 1.0), 0.5 * (h.z + 1.0));
        }
    }
}

// `v` normalised, or zero.
fn safe_normalize2(v: vec2f) -> vec2f {
    let l = length(v);
    return select(vec2f(0.0), v / l, l > 0.0);
}
