//! The chart's name for a set of methods: "lecture", or the methods that differ from the
//! lecture's, e.g. "sphere=stable".

use obscura::Methods;
use obscura::methods::MethodName;

/// Each method of `methods` that is not the lecture's, as (kind, name): ("sphere", "stable").
pub fn changes(methods: &Methods) -> Vec<(&'static str, &'static str)> {
    let base = Methods::LECTURE;
    [
        (
            methods.sphere != base.sphere,
            "sphere",
            methods.sphere.name(),
        ),
        (
            methods.triangle != base.triangle,
            "triangle",
            methods.triangle.name(),
        ),
        (methods.roots != base.roots, "sqrt", methods.roots.name()),
        (methods.rays != base.rays, "rays", methods.rays.name()),
        (methods.bias != base.bias, "bias", methods.bias.name()),
    ]
    .into_iter()
    .filter(|&(differs, _, _)| differs)
    .map(|(_, kind, name)| (kind, name))
    .collect()
}

/// The name of `methods` in the chart and its CSV.
pub fn label(methods: &Methods) -> String {
    let changes: Vec<String> = changes(methods)
        .into_iter()
        .map(|(kind, name)| format!("{kind}={name}"))
        .collect();
    if changes.is_empty() {
        "lecture".to_owned()
    } else {
        changes.join(",")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use obscura::{BiasMethod, SphereMethod};

    #[test]
    fn names_what_differs_from_the_lecture() {
        assert_eq!(label(&Methods::LECTURE), "lecture");
        let both = Methods {
            sphere: SphereMethod::Stable,
            bias: BiasMethod::Exclude,
            ..Methods::LECTURE
        };
        assert_eq!(label(&both), "sphere=stable,bias=exclude");
    }
}
