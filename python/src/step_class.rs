//! The Python classes of one solver step: a frozen class holding the bem3d step, one
//! getter per field it shows (the field's value, documented with its units), and the
//! class's own methods (the pressure map, `__repr__`).

/// `step_class! { doc; Name { step: bem3d::Step, other: T, ... } getters { doc field: type,
/// ... } methods { ... } }`: the class, its getters reading `self.step.field`, and the
/// methods given.
macro_rules! step_class {
    (
        $(#[doc = $cdoc:literal])*
        $name:ident { step: $step:ty $(, $extra:ident: $ety:ty)* $(,)? }
        getters { $( $(#[doc = $doc:literal])* $field:ident: $ty:ty ),* $(,)? }
        methods { $($methods:tt)* }
    ) => {
        $(#[doc = $cdoc])*
        #[pyclass(module = "mrdw._mrdw", frozen)]
        pub struct $name {
            step: $step,
            $($extra: $ety,)*
        }

        #[pymethods]
        impl $name {
            $(
                $(#[doc = $doc])*
                #[getter]
                fn $field(&self) -> $ty {
                    self.step.$field
                }
            )*
            $($methods)*
        }
    };
}
