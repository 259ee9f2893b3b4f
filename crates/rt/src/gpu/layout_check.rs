//! Checks every GPU struct of `crate::layout` against naga's layout of the assembled WGSL:
//! the build already checks each against WGSL's layout rules (`gpu_struct!`), and this
//! checks those rules as `gpu_struct` writes them against naga's.

use std::collections::HashMap;

/// Each WGSL struct's size and its fields' names and offsets, from naga.
fn wgsl_layouts() -> HashMap<String, (u32, Vec<(String, u32)>)> {
    let mut out = HashMap::new();
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
    let wgsl = wgsl_layouts();
    let hosts = crate::layout::struct_layouts();
    assert!(hosts.len() >= 22, "{} GPU structs", hosts.len());
    for (name, size, fields) in hosts {
        let (wgsl_size, wgsl_fields) = wgsl.get(&name).unwrap_or_else(|| panic!("no WGSL struct {name}"));
        assert_eq!(size as u32, *wgsl_size, "size of {name}");
        let host: Vec<(String, u32)> = fields.iter().map(|&(f, o)| (f.to_owned(), o as u32)).collect();
        let wgsl: Vec<(String, u32)> =
            wgsl_fields.iter().filter(|(f, _)| !crate::gpu_struct::is_padding(f)).cloned().collect();
        assert_eq!(host, wgsl, "the fields and offsets of {name}");
    }
}
