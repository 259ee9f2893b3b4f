// Watertight ray–triangle intersection (Woop, Benthin & Wald, "Watertight
// Ray/Triangle Intersection", JCGT 2013). The ray is sheared so that it runs
// along +z; the edge functions of neighbouring triangles are computed from the
// same numbers, so a ray through a shared edge or vertex hits at least one of them.

//#include "constants.wgsl"
//#include "ray.wgsl"

struct ShearedRay {
    origin: vec3f,
    // Permutation putting the largest direction component last.
    kx: u32,
    ky: u32,
    kz: u32,
    shear: vec3f,
}

fn sheared_ray(origin: vec3f, direction: vec3f) -> ShearedRay {
    let a = abs(direction);
    var kz = 2u;
    if a.x > a.y && a.x > a.z {
        kz = 0u;
    } else if a.y > a.z {
        kz = 1u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    // Keep the winding: swapping x and y when the ray runs along −z.
    if direction[kz] < 0.0 {
        let t = kx;
        kx = ky;
        ky = t;
    }
    let dz = direction[kz];
    return ShearedRay(origin, kx, ky, kz, vec3f(direction[kx] / dz, direction[ky] / dz, 1.0 / dz));
}

struct TriangleHit {
    t: f32,
    // Barycentric weights of v1 and v2.
    b1: f32,
    b2: f32,
}

// Returns t = INFINITY when there is no hit in (0, t_max).
fn intersect_triangle(ray: ShearedRay, v0: vec3f, v1: vec3f, v2: vec3f, t_max: f32) -> TriangleHit {
    let miss = TriangleHit(INFINITY, 0.0, 0.0);
    let a = v0 - ray.origin;
    let b = v1 - ray.origin;
    let c = v2 - ray.origin;
    let ax = a[ray.kx] - ray.shear.x * a[ray.kz];
    let ay = a[ray.ky] - ray.shear.y * a[ray.kz];
    let bx = b[ray.kx] - ray.shear.x * b[ray.kz];
    let by = b[ray.ky] - ray.shear.y * b[ray.kz];
    let cx = c[ray.kx] - ray.shear.x * c[ray.kz];
    let cy = c[ray.ky] - ray.shear.y * c[ray.kz];
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    // An edge function of exactly zero counts as inside: both triangles that
    // share the edge see the same zero, so the ray cannot slip between them.
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return miss;
    }
    let det = u + v + w;
    if det == 0.0 {
        return miss;
    }
    let az = ray.shear.z * a[ray.kz];
    let bz = ray.shear.z * b[ray.kz];
    let cz = ray.shear.z * c[ray.kz];
    let t_scaled = u * az + v * bz + w * cz;
    // t = t_scaled / det must lie in (0, t_max); compared without dividing.
    if det < 0.0 {
        if t_scaled >= 0.0 || t_scaled < t_max * det {
            return miss;
        }
    } else if t_scaled <= 0.0 || t_scaled > t_max * det {
        return miss;
    }
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    // t must exceed its own rounding error (pbrt-v4 §6.8.7): a ray leaving a
    // point that lies exactly in the triangle's plane (the offset is zero
    // along an axis on which the point is exact) must not hit at a t that is rounding noise.
    let max_zt = max(abs(az), max(abs(bz), abs(cz)));
    let max_xt = max(abs(ax), max(abs(bx), abs(cx)));
    let max_yt = max(abs(ay), max(abs(by), abs(cy)));
    let delta_z = gamma(3.0) * max_zt;
    let delta_x = gamma(5.0) * (max_xt + max_zt);
    let delta_y = gamma(5.0) * (max_yt + max_zt);
    let delta_e = 2.0 * (gamma(2.0) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    let max_e = max(abs(u), max(abs(v), abs(w)));
    let delta_t = 3.0 * (gamma(3.0) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * abs(inv_det);
    if t <= delta_t {
        return miss;
    }
    return TriangleHit(t, v * inv_det, w * inv_det);
}
