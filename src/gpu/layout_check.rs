//! Checks every host mirror in `crate::layout` against naga's layout of the assembled WGSL.

use crate::layout::*;
use std::mem::{offset_of, size_of};

/// (name, size, [(field, offset)]) of a host struct.
type HostLayout = (&'static str, usize, Vec<(&'static str, usize)>);

macro_rules! host_layout {
    ($wgsl:literal, $t:ty, [$($field:ident),*]) => {
        ($wgsl, size_of::<$t>(), vec![$((stringify!($field), offset_of!($t, $field))),*])
    };
}

fn wgsl_layouts() -> std::collections::HashMap<String, (u32, Vec<(String, u32)>)> {
    let mut out = std::collections::HashMap::new();
    for source in crate::gpu::shader::full_sources_for_layout_checks() {
        let module = wgpu::naga::front::wgsl::parse_str(&source).expect("WGSL parses");
        let mut layouter = wgpu::naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).expect("layout");
        for (handle, ty) in module.types.iter() {
            if let (Some(name), wgpu::naga::TypeInner::Struct { members, span }) = (&ty.name, &ty.inner) {
                let fields = members.iter().map(|m| (m.name.clone().unwrap_or_default(), m.offset)).collect();
                assert_eq!(layouter[handle].size, *span);
                out.insert(name.clone(), (*span, fields));
            }
        }
    }
    out
}

#[test]
fn host_structs_match_wgsl_layouts() {
    let hosts: Vec<HostLayout> = vec![
        host_layout!(
            "Frame",
            GpuFrame,
            [
                camera_position,
                aperture_radius,
                camera_right,
                focus_distance,
                camera_up,
                width,
                camera_forward,
                height,
                view_half_extent,
                view_shift,
                orthographic,
                aperture_blades,
                blade_rotation,
                inv_aperture_ratio,
                sky_color,
                max_bounces,
                sample_base,
                samples_per_dispatch,
                seed,
                tlas_root,
                sun_direction,
                sun_one_minus_cos,
                sun_radiance,
                sun_select_probability,
                emitter_count,
                emitter_total_power,
                ris_candidates,
                clamp_luminance,
                clip_start,
                clip_end,
                equirectangular_range,
                fisheye_sensor,
                fisheye_fov,
                fisheye_lens,
                panorama,
                transparent_glass,
                sky_light_share,
                first_sample,
                camera_motion_steps,
                camera_motion
            ]
        ),
        host_layout!("BvhNode", GpuBvhNode, [a_min, a_link, a_max, a_count, b_min, b_link, b_max, b_count]),
        host_layout!(
            "WideNode",
            GpuWideNode,
            [
                origin,
                exponents_imask,
                child_base,
                primitive_base,
                child_meta,
                child_min_x,
                child_max_x,
                child_min_y,
                child_max_y,
                child_min_z,
                child_max_z
            ]
        ),
        host_layout!("Triangle", GpuTriangle, [v0, material, v1, v2]),
        host_layout!("TriangleShading", GpuTriangleShading, [n0, u0, n1, u1, n2, u2, v]),
        host_layout!("Texture", GpuTexture, [offset, width, height, levels, flags, transform_lod, u_row, v_row]),
        host_layout!(
            "Instance",
            GpuInstance,
            [world_to_object, node_offset, triangle_offset, material_base, material_override]
        ),
        host_layout!("ObjectSettings", GpuObjectSettings, [geometry_offset, frequency_multiplier, holdout]),
        host_layout!("MotionKey", GpuMotionKey, [rotation, translation, stretch_xx, stretch_a, stretch_b]),
        host_layout!("MotionMatrix", GpuMotionMatrix, [world_to_object]),
        host_layout!("Sphere", GpuSphere, [center, radius, material, k]),
        host_layout!(
            "Material",
            GpuMaterial,
            [
                base_color,
                diffuse,
                emission,
                specular,
                absorption,
                reflection,
                volume_emission,
                transmission,
                ior,
                alpha,
                emission_luminance,
                base_color_texture,
                metallic_roughness_texture,
                emission_texture,
                metallic,
                roughness,
                base_alpha,
                alpha_cutoff,
                normal_texture,
                normal_scale,
                specular_tint,
                coating_eta,
                coating_f0,
                sheen_roughness,
                anisotropy,
                anisotropy_rotation,
                coat_tint,
                coat,
                coat_alpha,
                coat_ior,
                second_uv_set,
                diffuse_roughness,
                sheen_tint,
                sheen,
                thin_film_thickness,
                thin_film_ior,
                bump_map_correction,
                thin_film_weight,
                coat_texture,
                coat_roughness_texture,
                coat_tint_texture,
                sheen_texture,
                sheen_tint_texture,
                anisotropy_texture,
                specular_tint_texture,
                tangent,
                diffuse_roughness_texture,
                thin_film_texture,
                thin_film_minimum,
                node_program,
                transmission_texture,
                transmission_factor,
                specular_level_texture,
                anisotropy_directions,
                coat_normal_texture,
                coat_normal_scale,
                mix_material,
                holdout,
                ior_texture,
                ior_minimum,
                coat_ior_minimum,
                thin_film_ior_minimum
            ]
        ),
        host_layout!("TriangleTangents", GpuTriangleTangents, [t0, t1, t2]),
        host_layout!("TriangleUvs", GpuTriangleUvs, [uv0, uv1, uv2]),
        host_layout!("Emitter", GpuEmitter, [primitive, instance, cdf]),
        host_layout!("Lamp", GpuLamp, [position, kind, emission, radius, axis_u, len_u, axis_v, len_v, normal, cdf]),
        host_layout!("LampInfo", GpuLampInfo, [count, sun_share, emitter_share, lamp_share]),
        host_layout!(
            "LightTreeNode",
            GpuLightTreeNode,
            [bounds_min, power, bounds_max, cos_theta_o, axis, cos_theta_e, link, flags]
        ),
        host_layout!(
            "Atmosphere",
            GpuAtmosphere,
            [
                rayleigh_scattering,
                bottom_radius,
                mie_scattering,
                top_altitude,
                mie_absorption,
                rayleigh_scale_height,
                ozone_absorption,
                mie_scale_height,
                ground_albedo,
                mie_g,
                ozone_center,
                ozone_half_width,
                ground_altitude,
                steps,
                transmittance_size,
                scattering_size,
                scattering_offset,
                ground_offset,
                multiple_scattering
            ]
        ),
        host_layout!(
            "Environment",
            GpuEnvironment,
            [to_image_x, width, to_image_y, height, to_image_z, strength, light_share, importance, srgb]
        ),
        host_layout!("TraceRay", GpuTraceRay, [origin, t_max, direction]),
        host_layout!("TraceHit", GpuTraceHit, [t, primitive, instance, overflowed, b1, b2]),
    ];
    let wgsl = wgsl_layouts();
    for (name, size, fields) in hosts {
        let (wgsl_size, wgsl_fields) = wgsl.get(name).unwrap_or_else(|| panic!("no WGSL struct {name}"));
        assert_eq!(size as u32, *wgsl_size, "size of {name}");
        for (field, offset) in fields {
            let wgsl_offset = wgsl_fields.iter().find(|(f, _)| f == field).map(|(_, o)| *o);
            assert_eq!(Some(offset as u32), wgsl_offset, "offset of {name}.{field}");
        }
    }
}
