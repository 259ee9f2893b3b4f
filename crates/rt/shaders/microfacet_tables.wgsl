// Cycles' precomputed microfacet albedo tables (src/gpu/microfacet_tables.bin, baked by
// scripts/make_microfacet_tables.py), read with Cycles' linear interpolation
// (`lookup_table_read_*`). Axes: rough = √α, mu = cos θ of the viewer, z = F0^¼
// for an index (`microfacet_table_z`).

//#include "microfacet_tables.bindings.wgsl"

const TABLE_GGX_E: u32 = 0u; // [32 mu][32 rough]
const TABLE_GGX_EAVG: u32 = 1024u; // [32 rough]
const TABLE_GLASS_E: u32 = 1056u; // [16 z][16 mu][16 rough], index > 1
const TABLE_GLASS_EAVG: u32 = 5152u; // [16 z][16 rough]
const TABLE_GLASS_INV_E: u32 = 5408u; // the same for 1 / index
const TABLE_GLASS_INV_EAVG: u32 = 9504u;
const TABLE_GEN_SCHLICK_IOR_S: u32 = 9760u; // [16 z][16 mu][16 rough]

fn table_1d(offset: u32, size: u32, x: f32) -> f32 {
    let t = saturate(x) * f32(size - 1u);
    let i = min(u32(t), size - 1u);
    let j = min(i + 1u, size - 1u);
    let f = t - f32(i);
    return mix(microfacet_tables[offset + i], microfacet_tables[offset + j], f);
}

fn table_2d(offset: u32, nx: u32, ny: u32, x: f32, y: f32) -> f32 {
    let t = saturate(y) * f32(ny - 1u);
    let i = min(u32(t), ny - 1u);
    let j = min(i + 1u, ny - 1u);
    let f = t - f32(i);
    return mix(table_1d(offset + nx * i, nx, x), table_1d(offset + nx * j, nx, x), f);
}

fn table_3d(offset: u32, n: u32, x: f32, y: f32, z: f32) -> f32 {
    let t = saturate(z) * f32(n - 1u);
    let i = min(u32(t), n - 1u);
    let j = min(i + 1u, n - 1u);
    let f = t - f32(i);
    return mix(table_2d(offset + n * n * i, n, n, x, y), table_2d(offset + n * n * j, n, n, x, y), f);
}

// The tables' z axis for an index above 1.
fn microfacet_table_z(eta: f32) -> f32 {
    return sqrt(abs((eta - 1.0) / (eta + 1.0)));
}

// Mean over the reflected directions of where the real Fresnel curve of index `eta` lies
// between its F0 and 1 (Cycles' `ggx_gen_schlick_ior_s`): a rough coating's albedo is
// mix(F0, 1, s).
fn coating_fresnel_s(rough: f32, mu: f32, eta: f32) -> f32 {
    return table_3d(TABLE_GEN_SCHLICK_IOR_S, 16u, rough, mu, microfacet_table_z(eta));
}
