//! The pipeline's feature flags, declared once: `feature_set!` makes the `FeatureSet`
//! struct and a table of its flags (name, role, what each needs), from which the shader
//! assembler's flag names, the printed feature list, the all-features pipeline, the
//! pairwise covering array (`gpu::shader::covering`) and `rt bench effects`' forced rows
//! are all read. Adding an effect is one line here, its derivation in `analyse` and the
//! shader code that its `//#if` guards.

/// What a flag stands for, which decides where it is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// Code for something in the scene: on in the all-features pipeline, and `rt bench
    /// effects` prices it by forcing it on where the scene lacks it.
    Effect,
    /// A choice of how the scene is sampled or seen: on in the all-features pipeline but
    /// not forced on by `rt bench effects` (it would change the picture or its noise).
    Setting,
    /// An output a render (or the film) asks for: off in the all-features pipeline, not priced.
    Output,
    /// An output a render asks for, whose price `rt bench effects` shows.
    PricedOutput,
}

/// One boolean flag of a [`FeatureSet`](super::FeatureSet).
pub struct Flag {
    /// The field's name, which is the flag's name in `//#if` lines.
    pub name: &'static str,
    pub role: Role,
    /// Flags (or derived flags: `glass`, `nee`) whose code this one's code calls.
    pub needs: &'static [&'static str],
    pub get: fn(&super::FeatureSet) -> bool,
    pub set: fn(&mut super::FeatureSet, bool),
}

impl Flag {
    /// On in the pipeline a scene would run without specialisation.
    pub fn in_all_features(&self) -> bool {
        matches!(self.role, Role::Effect | Role::Setting)
    }

    /// Forced on by `rt bench effects` where a scene lacks it.
    pub fn priced(&self) -> bool {
        matches!(self.role, Role::Effect | Role::PricedOutput)
    }

    /// The name `rt info` prints (`coat-normal`).
    pub fn label(&self) -> String {
        self.name.replace('_', "-")
    }

    /// The name `rt bench effects` gives its row (`coat normal`).
    pub fn words(&self) -> String {
        self.name.replace('_', " ")
    }
}

/// Declares `FeatureSet`: its fields that are not flags, then each flag with its
/// documentation, its [`Role`] and the flags it needs.
macro_rules! feature_set {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $($(#[doc = $choice_doc:literal])* pub $choice:ident: $choice_ty:ty,)*
        }
        flags {
            $($(#[doc = $doc:literal])* $flag:ident: $role:ident $(needs $($need:ident),+)?;)*
        }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $($(#[doc = $choice_doc])* pub $choice: $choice_ty,)*
            $($(#[doc = $doc])* pub $flag: bool,)*
        }

        /// Every boolean flag of the feature set, in declaration order.
        pub const FLAGS: &[$crate::scene::feature_flags::Flag] = &[$($crate::scene::feature_flags::Flag {
            name: stringify!($flag),
            role: $crate::scene::feature_flags::Role::$role,
            needs: &[$($(stringify!($need)),+)?],
            get: |f: &$name| f.$flag,
            set: |f: &mut $name, on: bool| f.$flag = on,
        }),*];

        impl $name {
            /// The set with these values of the fields that are not flags, and every flag off.
            pub fn with_flags_off($($choice: $choice_ty),*) -> Self {
                Self { $($choice,)* $($flag: false,)* }
            }
        }
    };
}

pub(super) use feature_set;

/// The flag named `name`, if it is one of the set's own (not a derived one).
pub fn named(name: &str) -> Option<&'static Flag> {
    super::features::FLAGS.iter().find(|f| f.name == name)
}
