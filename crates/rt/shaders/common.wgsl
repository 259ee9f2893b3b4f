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

//#include "common.bindings.wgsl"
