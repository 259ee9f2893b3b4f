//! GPU structs declared once. [`gpu_struct!`] declares a struct the host uploads and the
//! shaders read: it makes the `#[repr(C)]` Rust type, checks **at compile time** that every
//! field sits at the offset WGSL's layout rules give it (and the size is WGSL's), and
//! writes the WGSL declaration, with the Rust docs as its comments, that the shaders
//! include as the file `NAME.struct.wgsl` (see `gpu::shader`).
//!
//! Why a `macro_rules!` macro rather than a schema file or a derive: the WGSL is assembled
//! at run time by the binary that holds the Rust types, so the declaration the shaders see
//! is made from the Rust one and cannot differ from it; a wrong offset stops the build with
//! the struct's and the field's name. A schema would add a build script and a second
//! syntax; a derive, a proc-macro crate.

/// A Rust type's WGSL counterpart: its name there, and WGSL's alignment and size of it.
pub trait WgslType {
    const ALIGN: usize;
    const SIZE: usize;
    fn wgsl_name() -> String;
}

/// A struct declared by [`gpu_struct!`].
pub trait GpuStruct: WgslType {
    /// The WGSL declaration, the Rust docs its comments.
    fn wgsl_declaration() -> String;
    /// Each field's name and Rust offset, in order.
    fn field_offsets() -> Vec<(&'static str, usize)>;
}

macro_rules! wgsl_type {
    ($t:ty, $name:literal, $align:literal, $size:literal) => {
        impl WgslType for $t {
            const ALIGN: usize = $align;
            const SIZE: usize = $size;
            fn wgsl_name() -> String {
                $name.to_owned()
            }
        }
    };
}

wgsl_type!(f32, "f32", 4, 4);
wgsl_type!(u32, "u32", 4, 4);
wgsl_type!([f32; 2], "vec2f", 8, 8);
wgsl_type!([f32; 3], "vec3f", 16, 12);
wgsl_type!([f32; 4], "vec4f", 16, 16);
wgsl_type!([u32; 2], "vec2u", 8, 8);
// Padding only (see `is_padding`), declared word by word.
wgsl_type!([u32; 3], "array<u32, 3>", 4, 12);
// Bytes packed into words.
wgsl_type!([u8; 4], "u32", 4, 4);
wgsl_type!([u8; 8], "vec2u", 8, 8);
// Matrix rows.
wgsl_type!([[f32; 4]; 3], "array<vec4f, 3>", 16, 48);

/// Declares a GPU struct once (see the module's documentation): a struct of `pub` fields
/// whose types implement [`WgslType`], named `as` the WGSL struct; `Clone`, `Copy`,
/// `Pod` and `Zeroable` are derived, other derives are given.
macro_rules! gpu_struct {
    (
        $(#[doc = $doc:literal])*
        #[derive($($derive:ident),* $(,)?)]
        pub struct $name:ident as $wgsl:literal {
            $(
                $(#[doc = $field_doc:literal])*
                pub $field:ident: $ty:ty
            ),* $(,)?
        }
    ) => {
        $(#[doc = $doc])*
        #[repr(C)]
        #[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable, $($derive),*)]
        pub struct $name {
            $(
                $(#[doc = $field_doc])*
                pub $field: $ty,
            )*
        }

        impl $crate::gpu_struct::WgslType for $name {
            const ALIGN: usize = {
                let mut align = 1;
                $(
                    let field_align = $crate::gpu_struct::field_align(
                        stringify!($field),
                        <$ty as $crate::gpu_struct::WgslType>::ALIGN,
                    );
                    if field_align > align {
                        align = field_align;
                    }
                )*
                align
            };
            const SIZE: usize = std::mem::size_of::<$name>();
            fn wgsl_name() -> String {
                $wgsl.to_owned()
            }
        }

        impl<const N: usize> $crate::gpu_struct::WgslType for [$name; N] {
            const ALIGN: usize = <$name as $crate::gpu_struct::WgslType>::ALIGN;
            const SIZE: usize = N * std::mem::size_of::<$name>();
            fn wgsl_name() -> String {
                format!("array<{}, {N}>", $wgsl)
            }
        }

        impl $crate::gpu_struct::GpuStruct for $name {
            fn wgsl_declaration() -> String {
                let mut out = String::new();
                $crate::gpu_struct::push_comment(&mut out, "", &[$($doc),*]);
                out.push_str(concat!("struct ", $wgsl, " {\n"));
                $(
                    if $crate::gpu_struct::is_padding(stringify!($field)) {
                        $crate::gpu_struct::push_padding(&mut out, stringify!($field), std::mem::size_of::<$ty>());
                    } else {
                        $crate::gpu_struct::push_comment(&mut out, "    ", &[$($field_doc),*]);
                        let ty = <$ty as $crate::gpu_struct::WgslType>::wgsl_name();
                        out.push_str(&format!(concat!("    ", stringify!($field), ": {},\n"), ty));
                    }
                )*
                out.push_str("}\n");
                out
            }

            fn field_offsets() -> Vec<(&'static str, usize)> {
                let all = [$((stringify!($field), std::mem::offset_of!($name, $field))),*];
                all.into_iter().filter(|(field, _)| !$crate::gpu_struct::is_padding(field)).collect()
            }
        }

        $crate::gpu_struct::check_wgsl_layout!($name; $($field: $ty),*);
    };
}

pub(crate) use gpu_struct;

/// The compile-time half of [`gpu_struct!`]: WGSL's layout of the fields (each at the next
/// multiple of its alignment, the size a multiple of the largest) against Rust's.
macro_rules! check_wgsl_layout {
    ($name:ident; $($field:ident: $ty:ty),*) => {
        // A mismatch does not build.
        const _: () = {
            let mut end = 0usize;
            let mut align = 1usize;
            $(
                let field_align =
                    $crate::gpu_struct::field_align(stringify!($field), <$ty as $crate::gpu_struct::WgslType>::ALIGN);
                let field_size = if $crate::gpu_struct::is_padding(stringify!($field)) {
                    std::mem::size_of::<$ty>()
                } else {
                    <$ty as $crate::gpu_struct::WgslType>::SIZE
                };
                end = end.next_multiple_of(field_align);
                assert!(
                    std::mem::offset_of!($name, $field) == end,
                    concat!(
                        stringify!($name), ".", stringify!($field),
                        " is not at the offset WGSL gives it: pad the struct to WGSL's alignment"
                    )
                );
                end += field_size;
                if field_align > align {
                    align = field_align;
                }
            )*
            assert!(
                std::mem::size_of::<$name>() == end.next_multiple_of(align),
                concat!("the size of ", stringify!($name), " is not WGSL's: pad its end to WGSL's alignment")
            );
        };
    };
}

pub(crate) use check_wgsl_layout;

/// The WGSL declarations of `structs`, served to the shaders as `NAME.struct.wgsl`.
macro_rules! gpu_struct_files {
    ($($name:ident),* $(,)?) => {
        /// The WGSL declaration of the GPU struct named `wgsl_name` in the shaders.
        pub fn struct_declaration(wgsl_name: &str) -> Option<String> {
            use $crate::gpu_struct::{GpuStruct, WgslType};
            $(
                if wgsl_name == <$name as WgslType>::wgsl_name() {
                    return Some(<$name as GpuStruct>::wgsl_declaration());
                }
            )*
            None
        }

        /// (WGSL name, size, each field's name and offset) of every GPU struct, for the test
        /// that checks them against naga's layout of the assembled shaders.
        #[cfg(test)]
        pub fn struct_layouts() -> Vec<(String, usize, Vec<(&'static str, usize)>)> {
            use $crate::gpu_struct::{GpuStruct, WgslType};
            vec![$((
                <$name as WgslType>::wgsl_name(),
                std::mem::size_of::<$name>(),
                <$name as GpuStruct>::field_offsets(),
            )),*]
        }
    };
}

pub(crate) use gpu_struct_files;

/// Whether a field is padding (`_pad…`): u32 words that only bring the next field to where
/// WGSL aligns it, or the struct's end to its WGSL size. WGSL declares them word by word
/// (`_pad0_0: u32`, …): an array of words would break uniform buffers' stride rule.
pub const fn is_padding(field: &str) -> bool {
    let b = field.as_bytes();
    b.len() >= 4 && b[0] == b'_' && b[1] == b'p' && b[2] == b'a' && b[3] == b'd'
}

/// WGSL's alignment of `field`, whose type's is `type_align`: a padding field's words are
/// u32s, aligned to 4.
pub const fn field_align(field: &str, type_align: usize) -> usize {
    if is_padding(field) { 4 } else { type_align }
}

/// Appends the WGSL members of padding field `field` of `bytes` bytes: a u32 per word.
pub fn push_padding(out: &mut String, field: &str, bytes: usize) {
    for word in 0..bytes / 4 {
        out.push_str(&format!("    {field}_{word}: u32,\n"));
    }
}

/// Appends `docs` (a Rust doc comment's lines) as WGSL comments indented by `indent`.
pub fn push_comment(out: &mut String, indent: &str, docs: &[&str]) {
    for line in docs {
        let text = line.strip_prefix(' ').unwrap_or(line);
        out.push_str(indent);
        out.push_str(if text.is_empty() { "//" } else { "// " });
        out.push_str(text);
        out.push('\n');
    }
}
