//! Area lights (`LightDesc::radius`, `SceneDesc::shadow_samples`): a point light or one shadow
//! ray draws the hard shadows of before, bit for bit; more find the share of a disc light a
//! point sees as geometry says.

mod common;

use common::render;
use core::f64::consts::PI;
use obscura::pattern::SampleId;
use obscura::{
    BiasMethod, CameraDesc, I16F16, LightDesc, MaterialDesc, Methods, ObjectDesc, Ray, Scalar,
    Scene, SceneDesc, ShapeDesc, Vec3, scenes,
};

/// A zero radius, or a single shadow ray, aims at the light's centre: today's images.
#[test]
fn a_point_light_or_one_shadow_ray_draws_the_hard_shadows_bit_for_bit() {
    fn frames<S: Scalar>() {
        let hard = render::<S>(&scenes::WHITTED, 48, 48, Methods::LECTURE).0;
        let wide = [LightDesc {
            radius: 2.0,
            ..scenes::WHITTED.lights[0]
        }];
        let one_ray = SceneDesc {
            lights: &wide,
            ..scenes::WHITTED
        };
        let point_many_rays = SceneDesc {
            shadow_samples: 16,
            ..scenes::WHITTED
        };
        for desc in [one_ray, point_many_rays] {
            let frame = render::<S>(&desc, 48, 48, Methods::LECTURE).0;
            assert!(frame.pixels == hard.pixels, "{}: {desc:?}", S::NAME);
        }
        // Sixteen rays over the disc do change the image: the test above can fail.
        let soft = SceneDesc {
            shadow_samples: 16,
            ..one_ray
        };
        assert!(render::<S>(&soft, 48, 48, Methods::LECTURE).0.pixels != hard.pixels);
    }
    frames::<f64>();
    frames::<f32>();
    frames::<I16F16>();
}

/// The disc light: radius 1, centred 4 above the floor's origin.
const LIGHT_HEIGHT: f64 = 4.0;
const LIGHT_RADIUS: f64 = 1.0;
const EYE: [f64; 3] = [0.0, 1.0, -10.0];

/// `objects` under `lights`, seen from `EYE`, lit by nothing else, taking 256 shadow rays (all
/// of them, or adaptively).
fn floor_scene<'a>(
    objects: &'a [ObjectDesc],
    lights: &'a [LightDesc],
    adaptive_shadows: bool,
) -> SceneDesc<'a> {
    SceneDesc {
        camera: CameraDesc::pinhole(EYE.map(|c| c as f32), [0.0; 3], [0.0, 1.0, 0.0], 40.0),
        objects,
        lights,
        ambient: [0.0; 3],
        far: 25.0,
        max_depth: 0,
        shadow_samples: 256,
        adaptive_shadows,
        ..SceneDesc::DEFAULT
    }
}

/// The floor: a white matte plane through the origin, facing +y.
const FLOOR: ObjectDesc = ObjectDesc {
    shape: ShapeDesc::Plane {
        point: [0.0; 3],
        normal: [0.0, 1.0, 0.0],
        checker: None,
    },
    material: MaterialDesc::matte([1.0; 3]),
};

/// The red of floor point (`x`, 0, 0) among `objects` under `light`, as format `S` traces it by
/// `methods` with 256 shadow rays (all, or adaptively).
fn red<S: Scalar>(
    objects: &[ObjectDesc],
    light: LightDesc,
    x: f64,
    adaptive: bool,
    methods: Methods,
) -> f64 {
    let to_point = [x - EYE[0], -EYE[1], -EYE[2]];
    let length = to_point.iter().map(|c| c * c).sum::<f64>().sqrt();
    let [dx, dy, dz] = to_point.map(|c| S::from_f64(c / length).expect("a unit vector fits"));
    let ray = Ray::new(Vec3::new(S::ZERO, S::ZERO, S::ZERO), Vec3::new(dx, dy, dz));
    let lights = [light];
    let desc = floor_scene(objects, &lights, adaptive);
    let scene = Scene::<S, 4, 1, 2>::build_with(&desc, methods).expect("the scene builds");
    scene.trace(ray, SampleId::default()).colour.r.to_f64()
}

/// The share of the light that floor point (`x`, 0, 0) sees past `occluder`, as format `S`
/// traces it with 256 shadow rays (all, or adaptively): its colour over its colour without
/// the occluder.
fn seen<S: Scalar>(occluder: ObjectDesc, x: f64, adaptive: bool) -> f64 {
    let light = LightDesc {
        radius: LIGHT_RADIUS as f32,
        ..LightDesc::point([0.0, LIGHT_HEIGHT as f32, 0.0], [1.0; 3])
    };
    let lecture = Methods::LECTURE;
    red::<S>(&[FLOOR, occluder], light, x, adaptive, lecture)
        / red::<S>(&[FLOOR], light, x, adaptive, lecture)
}

/// The area of the part of a unit disc beyond a chord `h` from its centre, over the disc's.
fn segment(h: f64) -> f64 {
    (h.acos() - h * (1.0 - h * h).sqrt()) / PI
}

/// A sphere on the light's axis, seen from the floor point below the light, is a disc centred
/// on the light's: it hides the share (r/R)² of it, r the radius of its silhouette's cone where
/// it meets the light's plane. Within 2 % of the geometry with 256 rays, in every format.
#[test]
fn a_sphere_on_the_axis_hides_its_silhouettes_share_of_the_light() {
    fn check<S: Scalar>() {
        let radius = 0.3_f64;
        for height in [1.5, 2.0, 2.5] {
            let sphere = ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: [0.0, height as f32, 0.0],
                    radius: radius as f32,
                },
                material: MaterialDesc::matte([0.5; 3]),
            };
            let silhouette = LIGHT_HEIGHT * (radius / height).asin().tan();
            let want = 1.0 - (silhouette / LIGHT_RADIUS).powi(2);
            let got = seen::<S>(sphere, 0.0, false);
            assert!(
                (got - want).abs() < 0.02,
                "{}: sphere at {height}: {got} of the light seen, geometry says {want}",
                S::NAME
            );
        }
    }
    check::<f64>();
    check::<f32>();
    check::<I16F16>();
}

/// A wide triangle at half the light's height, over x > 0, with its edge straight along z.
const EDGE: ObjectDesc = ObjectDesc {
    shape: ShapeDesc::Triangle {
        vertices: [[0.0, 2.0, -10.0], [0.0, 2.0, 10.0], [10.0, 2.0, 0.0]],
    },
    material: MaterialDesc::matte([0.5; 3]),
};

/// [`EDGE`], over x > 0, with its edge straight along z:
/// from a floor point, the plane through the point and the edge cuts the disc (which faces the
/// point) along a chord, and hides the part on the triangle's side. In full light and in full
/// shadow the first shadow rays agree and the answer is exact.
#[test]
fn an_edge_hides_the_segment_of_the_light_beyond_its_plane() {
    let edge_height = LIGHT_HEIGHT / 2.0;
    let geometry = |x: f64| {
        let p = [x, 0.0, 0.0];
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let unit = |a: [f64; 3]| a.map(|c| c / dot(a, a).sqrt());
        // The plane through p and the edge (along z through (0, h, 0)): normal (edge × (e − p)).
        let to_edge = sub([0.0, edge_height, 0.0], p);
        let normal = unit([-to_edge[1], to_edge[0], 0.0]);
        let to_light = sub([0.0, LIGHT_HEIGHT, 0.0], p);
        let facing = unit(to_light);
        // The chord's distance from the disc's centre, within the disc's plane.
        let off = dot(normal, to_light);
        let h = off.abs() / (1.0 - dot(normal, facing).powi(2)).sqrt() / LIGHT_RADIUS;
        let covered = sub([1.0, edge_height, 0.0], p);
        let centre_hidden = off.signum() == dot(normal, covered).signum();
        let hidden = if h >= 1.0 {
            f64::from(u8::from(centre_hidden))
        } else if centre_hidden {
            1.0 - segment(h)
        } else {
            segment(h)
        };
        1.0 - hidden
    };
    fn check<S: Scalar>(triangle: ObjectDesc, geometry: impl Fn(f64) -> f64) {
        for x in [-3.0, -0.75, -0.4, 0.0, 0.3, 0.7, 3.0] {
            let want = geometry(x);
            let got = seen::<S>(triangle, x, false);
            if want == 0.0 || want == 1.0 {
                assert_eq!(got, want, "{} at x = {x}", S::NAME);
            }
            assert!(
                (got - want).abs() < 0.02,
                "{} at x = {x}: {got} of the light seen, geometry says {want}",
                S::NAME
            );
        }
    }
    assert!((geometry(0.0) - 0.5).abs() < 1e-12);
    check::<f64>(EDGE, geometry);
    check::<f32>(EDGE, geometry);
    check::<I16F16>(EDGE, geometry);
}

/// Adaptive shadow rays answer exactly in full light and in full shadow, where the first four
/// agree. Right below the edge it splits the disc along the axis its four quarters meet on
/// (the disc's axes are x and z there), so two of the first four rays are blocked: the point
/// spends all 256 and draws what it draws without adaptive rays, bit for bit. At the
/// penumbra's outer fringe the edge hides 9 % of the disc and the first four all miss it: the
/// point stops there and is drawn in full light, the price of the rays it saves.
#[test]
fn adaptive_shadow_rays_spend_the_rest_where_the_first_disagree() {
    fn check<S: Scalar>() {
        assert_eq!(seen::<S>(EDGE, -3.0, true), 1.0, "{}", S::NAME);
        assert_eq!(seen::<S>(EDGE, 3.0, true), 0.0, "{}", S::NAME);
        let below = seen::<S>(EDGE, 0.0, true);
        assert_eq!(below, seen::<S>(EDGE, 0.0, false), "{}", S::NAME);
        assert!((below - 0.5).abs() < 0.02, "{}: {below}", S::NAME);
        let fringe = seen::<S>(EDGE, -0.75, false);
        assert!((fringe - 0.91).abs() < 0.01, "{}: {fringe}", S::NAME);
        assert_eq!(seen::<S>(EDGE, -0.75, true), 1.0, "{}", S::NAME);
    }
    check::<f64>();
    check::<f32>();
    check::<I16F16>();
}

/// A disc light shrinking to a point converges to the point's hard shadow (a ball's, on a
/// floor, 64×64): no more pixels differ from it at each tenth of the radius (about 100 at 0.5,
/// one at 0.005), none at 10⁻⁶; in `i16f16` that radius is below the format's resolution,
/// rounds to 0 and makes the light a point.
#[test]
fn a_radius_shrinking_to_zero_converges_to_the_hard_shadow() {
    fn differing<S: Scalar>(radius: f32) -> usize {
        let objects = [
            ObjectDesc {
                shape: ShapeDesc::Plane {
                    point: [0.0; 3],
                    normal: [0.0, 1.0, 0.0],
                    checker: None,
                },
                material: MaterialDesc::matte([0.8; 3]),
            },
            ObjectDesc {
                shape: ShapeDesc::Sphere {
                    center: [0.0, 0.8, 0.0],
                    radius: 0.5,
                },
                material: MaterialDesc::matte([0.8; 3]),
            },
        ];
        let lights = |radius| {
            [LightDesc {
                radius,
                ..LightDesc::point([-3.0, 4.0, 1.0], [0.9; 3])
            }]
        };
        let (hard, soft) = (lights(0.0), lights(radius));
        let desc = |lights| SceneDesc {
            camera: CameraDesc::pinhole([0.0, 4.0, -4.5], [0.0, 0.0, 0.5], [0.0, 1.0, 0.0], 60.0),
            shadow_samples: 16,
            ..floor_scene(&objects, lights, false)
        };
        let [hard, soft] =
            [&hard, &soft].map(|l| render::<S>(&desc(l), 64, 64, Methods::LECTURE).0);
        hard.pixels
            .iter()
            .zip(&soft.pixels)
            .filter(|(h, s)| h != s)
            .count()
    }
    fn check<S: Scalar>() -> Vec<usize> {
        let counts: Vec<usize> = [0.5, 0.05, 0.005, 5e-4, 1e-6]
            .into_iter()
            .map(differing::<S>)
            .collect();
        assert!(counts[0] > 50, "{}: {counts:?}", S::NAME);
        assert!(
            counts.windows(2).all(|w| w[1] <= w[0]),
            "{}: {counts:?}",
            S::NAME
        );
        counts
    }
    assert_eq!(check::<f64>().last(), Some(&0));
    assert_eq!(check::<f32>().last(), Some(&0));
    assert_eq!(check::<I16F16>().last(), Some(&0));
}

/// A wall (a triangle in the plane z = 0, facing the eye) lit by a disc light beside it, its
/// centre 0.2 in front of the wall's plane and 3 to the side, its radius 1: clear of the wall
/// itself, but most of the disc lies behind the wall's plane. The wall hides that part from the
/// point (0, 0, 0) — the segment beyond the chord d·tan θ from the disc's centre, θ the
/// centre's elevation over the wall — by either bias method alike (by exclusion a shadow ray
/// never meets the surface it leaves, and that part would shine through the wall).
#[test]
fn a_surface_hides_the_part_of_a_disc_light_behind_it() {
    const WALL: ObjectDesc = ObjectDesc {
        shape: ShapeDesc::Triangle {
            vertices: [[-1.0, -5.0, 0.0], [-1.0, 5.0, 0.0], [9.0, 0.0, 0.0]],
        },
        material: MaterialDesc::matte([1.0; 3]),
    };
    fn check<S: Scalar>() {
        let centre = [-3.0, 0.0, -0.2];
        let point = LightDesc::point(centre.map(|c| c as f32), [1.0; 3]);
        let disc = LightDesc {
            radius: 1.0,
            ..point
        };
        let distance = centre.iter().map(|c| c * c).sum::<f64>().sqrt();
        let elevation = (0.2 / distance).asin();
        let want = 1.0 - segment(distance * elevation.tan());
        for bias in [BiasMethod::Epsilon, BiasMethod::Exclude] {
            let methods = Methods {
                bias,
                ..Methods::LECTURE
            };
            let got = red::<S>(&[WALL], disc, 0.0, false, methods)
                / red::<S>(&[WALL], point, 0.0, false, methods);
            assert!(
                (got - want).abs() < 0.02,
                "{} by {methods}: {got} of the disc seen, geometry says {want}",
                S::NAME
            );
        }
    }
    check::<f64>();
    check::<f32>();
    check::<I16F16>();
}
