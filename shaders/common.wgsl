// Shared declarations: GPU structs (declared in src/layout.rs), bindings, constants.

//#include "shared_constants.wgsl"

// The structs the host uploads are declared once, in src/layout.rs (`gpu_struct!`), which
// writes each `NAME.struct.wgsl`.
//#include "Frame.struct.wgsl"

//#include "MotionKey.struct.wgsl"

//#include "BvhNode.struct.wgsl"

//#include "WideNode.struct.wgsl"

//#include "Triangle.struct.wgsl"

//#include "TriangleShading.struct.wgsl"

//#include "Instance.struct.wgsl"

//#include "ObjectSettings.struct.wgsl"

//#include "Sphere.struct.wgsl"

//#include "Material.struct.wgsl"

//#include "TriangleTangents.struct.wgsl"

//#include "TriangleUvs.struct.wgsl"

//#include "Texture.struct.wgsl"

//#include "Emitter.struct.wgsl"

// Counters in the statistics buffer.
const STAT_STACK_OVERFLOW: u32 = 0u;

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<storage, read> nodes: array<BvhNode>;
@group(0) @binding(2) var<storage, read> triangles: array<Triangle>;
@group(0) @binding(3) var<storage, read> shading: array<TriangleShading>;
@group(0) @binding(4) var<storage, read> instances: array<Instance>;
@group(0) @binding(5) var<storage, read> tlas_primitives: array<u32>;
@group(0) @binding(6) var<storage, read> spheres: array<Sphere>;
@group(0) @binding(7) var<storage, read> materials: array<Material>;
@group(0) @binding(8) var<storage, read_write> stats: array<atomic<u32>>;
@group(0) @binding(9) var<storage, read> emitters: array<Emitter>;
@group(0) @binding(12) var<storage, read> wide_nodes: array<WideNode>;
//#if textures
@group(0) @binding(13) var<storage, read> textures: array<Texture>;
// RGBA8 texels, red in the low byte.
@group(0) @binding(14) var<storage, read> texels: array<u32>;
//#endif
//#if tangent_frames
@group(0) @binding(17) var<storage, read> tangent_frames: array<TriangleTangents>;
//#endif
//#if uv_sets
@group(0) @binding(19) var<storage, read> second_uvs: array<TriangleUvs>;
//#endif
//#if object_settings
@group(0) @binding(20) var<storage, read> object_settings: array<ObjectSettings>;
//#endif
