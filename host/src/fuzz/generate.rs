//! Random scene descriptions for the fuzzer: over every range a scene file accepts (sizes and
//! distances from 10⁻⁶ to 10⁶, near-degenerate geometry, grazing and narrow cameras, lights on
//! surfaces, extreme materials, area lights, lenses and several samples), with enough plausible
//! ones among them that every format builds some. A scene is a function of its seed alone.

use obscura::scene::range;
use obscura::{
    BackgroundDesc, CameraDesc, CheckerDesc, LightDesc, MaterialDesc, ObjectDesc, Pixels,
    ShapeDesc, Vec3, Y_UP,
};
use obscura_scene::{OwnedMeshes, OwnedScene};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// The most objects a generated scene has (the host holds 64).
const MAX_OBJECTS: usize = 8;
/// The most lights (the host holds 16).
const MAX_LIGHTS: usize = 4;
/// The most rays per pixel a generated scene takes.
const MAX_FUZZ_SAMPLES: u16 = 4;
/// The most shadow rays per area light a generated scene takes (more than
/// [`obscura::pattern::SHADOW_PROBES`], so that adaptive shadows stop early or go on).
const MAX_FUZZ_SHADOW_SAMPLES: u16 = 8;

/// The deepest ray tree (the host's stack holds 15 levels).
const MAX_DEPTH: u8 = 8;

/// A generated scene and the image size to render it at.
#[derive(Clone, Debug)]
pub struct Generated {
    /// The scene.
    pub scene: OwnedScene,
    /// Width and height in pixels: at most [`MAX_PIXELS`], now and then one of them very long.
    pub size: (u32, u32),
    /// For an eighth of the scenes of one ray a pixel through a pinhole, the scene with
    /// adaptive pixels, half of them with a small ball added in view, to be held to its exact
    /// pixels.
    pub blocks: Option<OwnedScene>,
}

/// The most pixels a generated image has: enough to see edges, few enough to try many scenes.
pub const MAX_PIXELS: u32 = 1024;

/// The scene of `seed`.
pub fn scene(seed: u64) -> Generated {
    let mut g = Generator(Pcg64::seed_from_u64(seed));
    g.scene()
}

/// The random source, with the distributions scenes are drawn from.
struct Generator(Pcg64);

impl Generator {
    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.0.random::<f64>()
    }

    /// Log-uniform in [lo, hi): every decade as likely.
    fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (self.uniform(lo.ln(), hi.ln())).exp()
    }

    /// True with probability `p`.
    fn chance(&mut self, p: f64) -> bool {
        self.0.random::<f64>() < p
    }

    /// A whole number in `0..n`.
    fn below(&mut self, n: usize) -> usize {
        self.0.random_range(0..n.max(1))
    }

    /// A weight in [0, 1], now and then exactly 0 or 1.
    fn weight(&mut self) -> f64 {
        match self.below(10) {
            0 => 0.0,
            1 => 1.0,
            _ => self.uniform(0.0, 1.0),
        }
    }

    /// A unit vector, uniform on the sphere.
    fn direction(&mut self) -> [f64; 3] {
        loop {
            let v = [0; 3].map(|_| self.uniform(-1.0, 1.0));
            let length = norm(v);
            if length > 1e-3 && length <= 1.0 {
                return v.map(|c| c / length);
            }
        }
    }

    /// A unit vector within about `spread` radians of `axis`.
    fn near(&mut self, axis: [f64; 3], spread: f64) -> [f64; 3] {
        let offset = self.direction();
        let v = add(axis, scale(offset, spread.min(2.0)));
        let length = norm(v);
        if length < 1e-9 {
            axis
        } else {
            scale(v, 1.0 / length)
        }
    }

    /// A colour with channels in [0, 1].
    fn colour(&mut self) -> [f32; 3] {
        [0; 3].map(|_| self.weight() as f32)
    }

    fn scene(&mut self) -> Generated {
        // Most scenes are of a size every format could hold; some are of any size at all.
        let unit = if self.chance(0.7) {
            self.log_uniform(0.1, 100.0)
        } else {
            self.log_uniform(1e-6, 1e6)
        };
        let eye = [0; 3].map(|_| self.uniform(-unit, unit));
        let forward = self.direction();
        let vfov = match self.below(10) {
            0 => self.log_uniform(1e-3, 1.0),
            1 => self.uniform(120.0, 179.999),
            _ => self.uniform(20.0, 100.0),
        };
        let up = if self.chance(0.05) {
            self.near(forward, 1e-3)
        } else if self.chance(0.5) {
            [0.0, 1.0, 0.0]
        } else {
            self.direction()
        };
        let mut reach = 0.0_f64;
        let mut objects = Vec::new();
        for _ in 0..self.below(MAX_OBJECTS + 1) {
            let (object, extent) = self.object(eye, forward, vfov, unit);
            reach = reach.max(extent);
            objects.push(object);
        }
        let mut lights = Vec::new();
        for _ in 0..self.below(MAX_LIGHTS + 1) {
            let (light, extent) = self.light(eye, &objects, unit);
            reach = reach.max(extent);
            lights.push(light);
        }
        let far = if reach == 0.0 {
            unit
        } else if self.chance(0.1) {
            reach * (1.0 + 1e-6)
        } else {
            reach * self.uniform(1.01, 3.0)
        };
        let look_at = add(eye, scale(forward, unit));
        let background = if self.chance(0.5) {
            BackgroundDesc::Solid(self.bright())
        } else {
            BackgroundDesc::Gradient {
                horizon: self.bright(),
                zenith: self.bright(),
                up: Y_UP,
            }
        };
        let scene = OwnedScene {
            camera: CameraDesc::pinhole(f32s(eye), f32s(look_at), f32s(up), vfov as f32),
            objects,
            meshes: OwnedMeshes::default(),
            lights,
            ambient: self.bright().map(|c| c * 0.3),
            background,
            far: far as f32,
            max_depth: self.0.random_range(0..=MAX_DEPTH),
            samples: 1,
            adaptive_samples: false,
            shadow_samples: 1,
            adaptive_shadows: false,
            pixels: Pixels::Exact,
            animation: None,
        };
        let size = self.size();
        // Drawn last, so that every other draw is what it was before scenes had an up.
        let mut scene = scene;
        if let BackgroundDesc::Gradient { up, .. } = &mut scene.background
            && self.chance(0.5)
        {
            *up = f32s(self.direction());
        }
        // A quarter of the scenes anti-aliased, by a few samples: the tries stay quick.
        if self.chance(0.25) {
            scene.samples = self.0.random_range(2..=MAX_FUZZ_SAMPLES);
        }
        // A quarter with area lights: each a disc from a ten-thousandth of its distance from
        // the eye to as wide as that (some reach out of the world or into a surface, and are
        // refused), taking a few shadow rays, adaptively or not.
        if self.chance(0.25) {
            for light in &mut scene.lights {
                let reach = norm(sub(f64s(light.position), eye)).max(1e-3);
                light.radius = (reach * self.log_uniform(1e-4, 1.0)) as f32;
            }
            scene.shadow_samples = self.0.random_range(2..=MAX_FUZZ_SHADOW_SAMPLES);
            scene.adaptive_shadows = self.chance(0.5);
        }
        // A quarter through a lens: from a ten-thousandth of the nearest surface's distance
        // to a little beyond it (refused: the lens reaches the surface), focused where the
        // camera looks or anywhere from a twentieth of the scene's unit to twenty of them.
        if self.chance(0.25) {
            let eye = Vec3::from_f32(scene.camera.eye);
            let nearest = scene
                .objects
                .iter()
                .map(|object| range::clearance(object, eye))
                .fold(unit, f64::min);
            scene.camera.aperture = (nearest * self.log_uniform(1e-4, 1.2)) as f32;
            if self.chance(0.5) {
                scene.camera.focus_distance = Some((unit * self.log_uniform(0.05, 20.0)) as f32);
            }
        }
        // An eighth of the scenes without a lens take adaptive samples (Whitted's corners),
        // split to 4 or 16 cells.
        if scene.camera.aperture == 0.0 && self.chance(0.125) {
            scene.samples = if self.chance(0.5) { 4 } else { 16 };
            scene.adaptive_samples = true;
        }
        // An eighth of the scenes on a grid of a power of two about an eighth of their unit:
        // every position a multiple of the cell, every plane facing along an axis with squares
        // of one to eight cells, so that eyes and lights stand on squares' edges and the scene
        // translates exactly by any multiple of the cell.
        if self.chance(0.125) {
            scene = self.on_a_grid(&scene, unit);
        }
        // A sixth with the world's edge at one of its objects: moved out to be the farthest
        // thing in the scene, `far` just short of it (refused: it pokes out of the world), at
        // it, or just beyond it, where the world cuts a small disc from a plane.
        if self.chance(1.0 / 6.0) {
            self.at_the_edge(&mut scene);
        }
        // A twelfth with a mesh (drawn after the rest, which stays what it was): a closed ball of
        // 8 or 32 triangles, its corners jittered or not, or a soup of triangles, now and then
        // with corners collapsed into triangles without area (left out), of any size, half
        // of them smooth (normals at the corners).
        if self.chance(1.0 / 12.0) {
            self.mesh(&mut scene, eye, forward, vfov, unit);
        }
        // Drawn after the mesh, likewise: a twentieth with a glass ball beside one of the
        // objects (most fixed formats refuse them: at a tenth, fewer than one build in ten of
        // the fuzzer's corpus is held to its prediction), a tenth with every surface matte (no
        // highlight, mirror or glass: the row pass's scenes).
        if self.chance(0.05) {
            self.glass_beside(&mut scene, eye);
        }
        if self.chance(0.1) {
            for object in &mut scene.objects {
                object.material = MaterialDesc {
                    specular: 0.0,
                    reflection: 0.0,
                    transmission: 0.0,
                    ..object.material
                };
            }
        }
        // Drawn last, likewise: an eighth of the scenes of one ray a pixel through a pinhole
        // again with adaptive pixels, in blocks of 2, 4 or 8, half of them with a ball one to
        // three pixels across in view: what a block would lose that filled over it.
        let mut blocks = None;
        if scene.samples == 1 && scene.camera.aperture == 0.0 && self.chance(0.125) {
            let mut adaptive = scene.clone();
            adaptive.pixels = Pixels::Adaptive(Pixels::BLOCKS[self.below(Pixels::BLOCKS.len())]);
            if self.chance(0.5) {
                self.small_ball(&mut adaptive, size.1);
            }
            blocks = Some(adaptive);
        }
        Generated {
            scene,
            size,
            blocks,
        }
    }

    /// Adds a ball of any material, from one to three pixels wide at the centre of an image `height` pixels high, somewhere in `scene`'s view, nearer than any
    /// other object.
    fn small_ball(&mut self, scene: &mut OwnedScene, height: u32) {
        let eye = f64s(scene.camera.eye);
        let forward = sub(f64s(scene.camera.look_at), eye);
        let forward = normalized(forward);
        let half = (f64::from(scene.camera.vfov_degrees) / 2.0)
            .to_radians()
            .tan();
        let aside = scale(self.direction(), 0.7 * half);
        let dir = add(forward, aside);
        let dir = normalized(dir);
        let eye_at = Vec3::from_f32(scene.camera.eye);
        let nearest = scene
            .objects
            .iter()
            .map(|object| range::clearance(object, eye_at))
            .fold(f64::from(scene.far), f64::min);
        let distance = nearest * self.uniform(0.2, 0.9);
        let pixel = 2.0 * half / f64::from(height.max(1));
        let radius = distance * pixel * self.uniform(1.0, 3.0) / 2.0;
        let material = self.material();
        scene.objects.push(ObjectDesc {
            shape: ShapeDesc::Sphere {
                center: f32s(add(eye, scale(dir, distance))),
                radius: radius as f32,
            },
            material,
        });
    }

    /// Adds a clear glass ball just clear of one of `scene`'s spheres or planes, or just
    /// inside it (the two overlap, a ray inside one meets the other), where the world holds
    /// it: refracted rays that leave a ball and meet a neighbour at once.
    fn glass_beside(&mut self, scene: &mut OwnedScene, eye: [f64; 3]) {
        let neighbours: Vec<([f64; 3], [f64; 3], f64)> = scene
            .objects
            .iter()
            .filter_map(|object| match object.shape {
                ShapeDesc::Sphere { center, radius } => {
                    Some((f64s(center), self.direction(), f64::from(radius)))
                }
                ShapeDesc::Plane { point, normal, .. } => {
                    let n = f64s(normal);
                    Some((f64s(point), normalized(n), 0.0))
                }
                _ => None,
            })
            .collect();
        if neighbours.is_empty() {
            return;
        }
        let (centre, outwards, radius) = neighbours[self.below(neighbours.len())];
        let size = if radius > 0.0 {
            radius * self.log_uniform(0.3, 2.0)
        } else {
            norm(sub(centre, eye)).max(1e-3) * self.log_uniform(1e-3, 0.3)
        };
        let gap = size * self.log_uniform(1e-4, 0.1);
        let gap = if self.chance(0.2) { -gap } else { gap };
        let ball = add(centre, scale(outwards, radius + size + gap));
        // Within the world the scene has (other draws widen it), and clear of the eye and the
        // lights (other draws put them on surfaces).
        let clear = |point: [f64; 3]| norm(sub(point, ball)) > 2.0 * size;
        if norm(sub(ball, eye)) + size >= f64::from(scene.far)
            || !clear(eye)
            || !scene.lights.iter().all(|light| clear(f64s(light.position)))
        {
            return;
        }
        scene.objects.push(ObjectDesc {
            shape: ShapeDesc::Sphere {
                center: f32s(ball),
                radius: size as f32,
            },
            material: MaterialDesc {
                colour: [1.0; 3],
                diffuse: 0.0,
                specular: self.weight() as f32,
                shininess: self.log_uniform(1.0, 1000.0) as u16,
                reflection: 0.1,
                transmission: 0.9,
                ior: self.uniform(1.0, 2.5) as f32,
            },
        });
    }

    /// Adds a mesh to `scene` (see [`Self::scene`]), widening the world to hold it.
    fn mesh(
        &mut self,
        scene: &mut OwnedScene,
        eye: [f64; 3],
        forward: [f64; 3],
        vfov: f64,
        unit: f64,
    ) {
        let spread = (vfov.to_radians() / 2.0).min(1.5) * self.uniform(0.0, 1.5);
        // Within the world the scene has (now and then beyond it, which widens it).
        let far = f64::from(scene.far);
        let distance = (unit * self.log_uniform(1e-3, 10.0)).min(far * self.uniform(0.1, 0.9));
        let centre = add(eye, scale(self.near(forward, spread), distance));
        let size = if self.chance(0.1) {
            distance * self.log_uniform(1e-7, 1e-4)
        } else if self.chance(0.9) {
            (far - distance) * self.log_uniform(0.05, 0.9)
        } else {
            distance * self.log_uniform(0.05, 3.0)
        };
        let (mut corners, triangles) = if self.chance(0.2) {
            // A soup: triangles anywhere within `size` of the centre.
            let n = 1 + self.below(40);
            let corners: Vec<[f64; 3]> = (0..3 * n).map(|_| self.direction()).collect();
            let triangles = (0..n as u32)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            (corners, triangles)
        } else {
            ball(self.chance(0.5))
        };
        let jitter = if self.chance(0.5) {
            self.log_uniform(1e-6, 0.3)
        } else {
            0.0
        };
        // Turned (most of the time), or skewed by a random linear map.
        let axes = if self.chance(0.7) {
            let u = self.direction();
            let v = cross(u, self.direction());
            [u, normalized(v)]
        } else {
            [self.direction(), self.direction()]
        };
        // Each corner's direction from the centre, mapped with it.
        let mut outwards = Vec::with_capacity(corners.len());
        for corner in &mut corners {
            let noise = scale(self.direction(), jitter);
            let p = add(*corner, noise);
            let [u, v] = axes;
            let w = cross(u, v);
            let mapped = add(add(scale(u, p[0]), scale(v, p[1])), scale(w, p[2]));
            *corner = add(centre, scale(mapped, size));
            outwards.push(mapped);
        }
        let mut triangles: Vec<[u32; 3]> = triangles;
        if self.chance(0.2) {
            for triangle in triangles.iter_mut().take(1 + self.below(4)) {
                triangle[2] = triangle[1];
            }
        }
        let vertices: Vec<[f32; 3]> = corners.iter().map(|&c| f32s(c)).collect();
        let material = self.material();
        // Half of them smooth, drawn last (the mesh is what it would be flat): each corner's
        // normal its direction from the centre (the surface's, where the map turns the ball),
        // now and then one left out.
        let mut normals = Vec::new();
        if self.chance(0.5) {
            for outward in outwards {
                let length = norm(outward);
                normals.push(if length > 1e-6 && !self.chance(0.05) {
                    f32s(scale(outward, 1.0 / length))
                } else {
                    [0.0; 3]
                });
            }
        }
        let Ok(added) = scene.meshes.add(&vertices, &normals, &triangles) else {
            return;
        };
        let extent = corners
            .iter()
            .map(|&c| norm(sub(c, eye)))
            .fold(0.0, f64::max);
        if extent >= f64::from(scene.far) {
            scene.far = (extent * self.uniform(1.01, 2.0)) as f32;
        }
        scene.objects.push(ObjectDesc {
            shape: ShapeDesc::Mesh { root: added.root },
            material,
        });
    }

    /// `scene` with the world's edge at one of its objects (see [`Self::scene`]): the object
    /// scaled about the eye until its farthest point (a plane's nearest) is as far as the
    /// farthest thing in the scene, and `far` that distance times 1 less 10⁻⁷ to 10⁻³, 1, or 1
    /// plus 10⁻⁷ to 10⁻².
    fn at_the_edge(&mut self, scene: &mut OwnedScene) {
        let eye = Vec3::from_f32(scene.camera.eye);
        let edge = |object: &ObjectDesc| match object.shape {
            ShapeDesc::Plane { .. } => range::clearance(object, eye),
            ShapeDesc::Sphere { center, radius } => {
                (Vec3::from_f32(center) - eye).length() + f64::from(radius)
            }
            ShapeDesc::Triangle { vertices } => vertices
                .iter()
                .map(|&v| (Vec3::from_f32(v) - eye).length())
                .fold(0.0, f64::max),
            // Its farthest corner: it counts for the farthest thing in the scene.
            ShapeDesc::Mesh { root } => {
                let meshes = scene.meshes.desc();
                meshes
                    .triangles_of(root)
                    .iter()
                    .flat_map(|&t| meshes.corners(t))
                    .map(|v| (Vec3::from_f32(v) - eye).length())
                    .fold(0.0, f64::max)
            }
        };
        let lights = scene
            .lights
            .iter()
            .map(|l| (Vec3::from_f32(l.position) - eye).length() + f64::from(l.radius));
        let farthest = scene
            .objects
            .iter()
            .map(edge)
            .chain(lights)
            .fold(0.0, f64::max);
        let at = f64s(scene.camera.eye);
        let target = self.below(scene.objects.len());
        if let Some(object) = scene.objects.get_mut(target) {
            let k = farthest / edge(object);
            if k.is_finite() {
                let out = |p: [f32; 3]| f32s(add(at, scale(sub(f64s(p), at), k)));
                object.shape = match object.shape {
                    ShapeDesc::Sphere { center, radius } => ShapeDesc::Sphere {
                        center: out(center),
                        radius: (f64::from(radius) * k) as f32,
                    },
                    ShapeDesc::Plane {
                        point,
                        normal,
                        checker,
                    } => ShapeDesc::Plane {
                        point: out(point),
                        normal,
                        checker,
                    },
                    ShapeDesc::Triangle { vertices } => ShapeDesc::Triangle {
                        vertices: vertices.map(out),
                    },
                    // A mesh stays where it is (its corners are shared in the scene's meshes).
                    mesh @ ShapeDesc::Mesh { .. } => mesh,
                };
            }
        }
        let factor = match self.below(3) {
            0 => 1.0 - self.log_uniform(1e-7, 1e-3),
            1 => 1.0,
            _ => 1.0 + self.log_uniform(1e-7, 1e-2),
        };
        let far = (farthest * factor) as f32;
        if far > 0.0 {
            scene.far = far;
        }
    }

    /// `scene` on a grid of cells of a power of two near `unit`/8 (see [`Self::scene`]).
    fn on_a_grid(&mut self, scene: &OwnedScene, unit: f64) -> OwnedScene {
        let cell = 2_f64.powi((unit / 8.0).log2().round() as i32);
        let snap = |p: [f32; 3]| p.map(|c| ((f64::from(c) / cell).round() * cell) as f32);
        let mut snapped = scene.transformed(snap, |d| d, |l| l);
        for object in &mut snapped.objects {
            if let ShapeDesc::Plane {
                normal, checker, ..
            } = &mut object.shape
            {
                let mut axis = [0.0; 3];
                axis[self.below(3)] = if self.chance(0.5) { 1.0 } else { -1.0 };
                *normal = axis;
                if let Some(checker) = checker {
                    checker.size = (cell * f64::from(1_u8 << self.below(4))) as f32;
                }
            }
        }
        snapped
    }

    /// Mostly a colour in [0, 1], now and then far brighter.
    fn bright(&mut self) -> [f32; 3] {
        let gain = if self.chance(0.1) {
            self.log_uniform(1.0, 1e3)
        } else {
            1.0
        };
        self.colour().map(|c| c * gain as f32)
    }

    /// An image size of at most [`MAX_PIXELS`], now and then a single long row or column.
    fn size(&mut self) -> (u32, u32) {
        if self.chance(0.05) {
            let long = self.0.random_range(1..=obscura::MAX_IMAGE_SIDE);
            return if self.chance(0.5) {
                (long, 1)
            } else {
                (1, long)
            };
        }
        let width = self.0.random_range(1..=48_u32);
        let height = self.0.random_range(1..=(MAX_PIXELS / width).min(48));
        (width, height)
    }

    /// An object somewhere in view (most of the time), and how far from the eye it reaches.
    fn object(
        &mut self,
        eye: [f64; 3],
        forward: [f64; 3],
        vfov: f64,
        unit: f64,
    ) -> (ObjectDesc, f64) {
        let spread = (vfov.to_radians() / 2.0).min(1.5) * self.uniform(0.0, 1.5);
        let distance = unit * self.log_uniform(1e-3, 10.0);
        let centre = add(eye, scale(self.near(forward, spread), distance));
        let (shape, extent) = match self.below(3) {
            0 => {
                let radius = distance * self.log_uniform(1e-5, 0.95);
                let shape = ShapeDesc::Sphere {
                    center: f32s(centre),
                    radius: radius as f32,
                };
                (shape, distance + radius)
            }
            1 => {
                let normal = match self.below(4) {
                    // Nearly containing the view direction: seen at a grazing angle.
                    0 => cross(forward, self.direction()),
                    1 => [0.0, 1.0, 0.0],
                    _ => self.direction(),
                };
                let checker = self.chance(0.5).then(|| CheckerDesc {
                    colour: self.colour(),
                    size: (unit * self.log_uniform(1e-5, 1e5)) as f32,
                });
                let shape = ShapeDesc::Plane {
                    point: f32s(centre),
                    normal: f32s(normal),
                    checker,
                };
                (shape, 0.0)
            }
            _ => {
                let size = distance * self.log_uniform(1e-4, 3.0);
                let a = add(centre, scale(self.direction(), size));
                let b = add(centre, scale(self.direction(), size));
                let c = match self.below(10) {
                    // A sliver: the third corner nearly on the line through the others.
                    0 => {
                        let along = add(a, scale(sub(b, a), self.uniform(-1.0, 2.0)));
                        add(
                            along,
                            scale(self.direction(), size * self.log_uniform(1e-8, 1e-1)),
                        )
                    }
                    // The eye on the triangle's plane, or on an edge.
                    1 => add(eye, scale(sub(eye, a), self.uniform(0.0, 1.0))),
                    _ => add(centre, scale(self.direction(), size)),
                };
                let vertices = [a, b, c];
                let extent = vertices
                    .iter()
                    .map(|&v| norm(sub(v, eye)))
                    .fold(0.0, f64::max);
                let shape = ShapeDesc::Triangle {
                    vertices: vertices.map(f32s),
                };
                (shape, extent)
            }
        };
        let material = self.material();
        (ObjectDesc { shape, material }, extent)
    }

    fn material(&mut self) -> MaterialDesc {
        let reflection = self.weight();
        let transmission = if self.chance(0.3) {
            self.uniform(0.0, 1.0 - reflection)
        } else {
            0.0
        };
        let material = MaterialDesc {
            colour: self.colour(),
            diffuse: self.weight() as f32,
            specular: self.weight() as f32,
            shininess: self.log_uniform(1.0, 65_535.0) as u16,
            reflection: reflection as f32,
            transmission: transmission as f32,
            ior: if self.chance(0.7) {
                self.uniform(1.0, 2.5)
            } else {
                self.log_uniform(1.0, 1e6)
            } as f32,
        };
        // A surface whose diffuse weight is 0 or 1 is matte (no highlight, mirror or
        // transmission), as the row pass takes a floor: one in five, decided by a draw
        // already made so that the seeds' other scenes stay as they were.
        if material.diffuse == 0.0 || material.diffuse == 1.0 {
            MaterialDesc {
                specular: 0.0,
                reflection: 0.0,
                transmission: 0.0,
                ..material
            }
        } else {
            material
        }
    }

    /// A light, now and then just off an object's surface, and how far from the eye it is.
    fn light(&mut self, eye: [f64; 3], objects: &[ObjectDesc], unit: f64) -> (LightDesc, f64) {
        let anchor = match objects.get(self.below(objects.len() * 2)) {
            Some(object) => match object.shape {
                ShapeDesc::Sphere { center, radius } => {
                    let out = self.direction();
                    let gap = f64::from(radius) * self.log_uniform(1e-7, 2.0);
                    add(f64s(center), scale(out, f64::from(radius) + gap))
                }
                ShapeDesc::Plane { point, normal, .. } => {
                    let n = f64s(normal);
                    let n = normalized(n);
                    let gap = unit * self.log_uniform(1e-7, 1.0);
                    let along = scale(self.direction(), unit * self.uniform(0.0, 2.0));
                    add(add(f64s(point), along), scale(n, gap))
                }
                ShapeDesc::Triangle { vertices } => {
                    let [a, b, c] = vertices.map(f64s);
                    let (u, v) = (self.uniform(0.0, 0.5), self.uniform(0.0, 0.5));
                    let on = add(a, add(scale(sub(b, a), u), scale(sub(c, a), v)));
                    let n = cross(sub(b, a), sub(c, a));
                    let n = normalized(n);
                    add(on, scale(n, unit * self.log_uniform(1e-7, 1.0)))
                }
                // Meshes are added after the lights.
                ShapeDesc::Mesh { .. } => eye,
            },
            None => add(
                eye,
                scale(self.direction(), unit * self.log_uniform(1e-2, 10.0)),
            ),
        };
        let intensity = if self.chance(0.1) {
            self.log_uniform(1e-3, 1e3)
        } else {
            1.0
        };
        let light = LightDesc::point(f32s(anchor), self.colour().map(|c| c * intensity as f32));
        (light, norm(sub(anchor, eye)))
    }
}

#[allow(clippy::cast_possible_truncation, reason = "a description is in f32")]
fn f32s(v: [f64; 3]) -> [f32; 3] {
    v.map(|c| c as f32)
}

fn f64s(v: [f32; 3]) -> [f64; 3] {
    v.map(f64::from)
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(a: [f64; 3], k: f64) -> [f64; 3] {
    a.map(|c| c * k)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a` made unit length (a vector of no length stays one).
fn normalized(a: [f64; 3]) -> [f64; 3] {
    scale(a, 1.0 / norm(a).max(1e-30))
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// A closed ball about the origin of radius 1: an octahedron of 8 triangles, or with `finer`
/// each cut into four and pushed out onto the sphere (32), anticlockwise from outside.
fn ball(finer: bool) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut corners = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces: [[u32; 3]; 8] = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    if !finer {
        return (corners, faces.to_vec());
    }
    let mut middle = |a: u32, b: u32| {
        let m = add(corners[a as usize], corners[b as usize]);
        corners.push(scale(m, 1.0 / norm(m)));
        (corners.len() - 1) as u32
    };
    let triangles = faces
        .iter()
        .flat_map(|&[a, b, c]| {
            let (ab, bc, ca) = (middle(a, b), middle(b, c), middle(c, a));
            [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
        })
        .collect();
    (corners, triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// How far a ball at `c` of radius `r` is from a sphere's or a plane's surface (negative
    /// where they overlap); infinite from other shapes.
    fn gap(shape: &ShapeDesc, c: [f64; 3], r: f64) -> f64 {
        match *shape {
            ShapeDesc::Sphere { center, radius } => {
                norm(sub(f64s(center), c)) - r - f64::from(radius)
            }
            ShapeDesc::Plane { point, normal, .. } => {
                let (n, along) = (f64s(normal), sub(c, f64s(point)));
                (along[0] * n[0] + along[1] * n[1] + along[2] * n[2]).abs() / norm(n) - r
            }
            _ => f64::INFINITY,
        }
    }

    #[test]
    fn a_scene_is_a_function_of_its_seed() {
        let (a, b) = (scene(7), scene(7));
        assert_eq!(a.scene, b.scene);
        assert_eq!(a.size, b.size);
        assert_ne!(scene(8).scene, a.scene);
    }

    #[test]
    fn sizes_stay_small_and_scenes_vary() {
        let scenes: Vec<Generated> = (0..500).map(scene).collect();
        for g in &scenes {
            let (w, h) = g.size;
            assert!(w * h <= obscura::MAX_IMAGE_SIDE.max(MAX_PIXELS), "{w}x{h}");
        }
        let kinds = |f: fn(&ShapeDesc) -> bool| {
            scenes
                .iter()
                .flat_map(|g| &g.scene.objects)
                .filter(|o| f(&o.shape))
                .count()
        };
        assert!(kinds(|s| matches!(s, ShapeDesc::Sphere { .. })) > 100);
        assert!(kinds(|s| matches!(s, ShapeDesc::Plane { .. })) > 100);
        assert!(kinds(|s| matches!(s, ShapeDesc::Triangle { .. })) > 100);
        assert!(kinds(|s| matches!(s, ShapeDesc::Mesh { .. })) > 25);
        let count = |f: fn(&OwnedScene) -> bool| scenes.iter().filter(|g| f(&g.scene)).count();
        assert!(count(|s| s.samples > 1) > 75);
        assert!(count(|s| s.lights.iter().any(|l| l.radius > 0.0)) > 75);
        assert!(count(|s| s.camera.aperture > 0.0) > 75);
        assert!(count(|s| s.camera.focus_distance.is_some()) > 30);
        assert!(scenes.iter().filter(|g| g.blocks.is_some()).count() > 15);
        // A level camera over a matte floor: the row pass's case.
        let row_passed = count(|s| {
            s.camera.up == [0.0, 1.0, 0.0]
                && s.objects.iter().any(|o| {
                    let m = &o.material;
                    matches!(
                        o.shape,
                        ShapeDesc::Plane {
                            normal: [0.0, 1.0, 0.0],
                            ..
                        }
                    ) && [m.specular, m.reflection, m.transmission] == [0.0; 3]
                })
        });
        assert!(
            row_passed > 10,
            "{row_passed} scenes with a level camera over a matte floor"
        );
        let matte_only = count(|s| {
            s.objects.len() > 1
                && s.objects.iter().all(|o| {
                    let m = &o.material;
                    [m.specular, m.reflection, m.transmission] == [0.0; 3]
                })
        });
        assert!(matte_only > 30, "{matte_only} scenes matte alone");
        // A glass ball within a tenth of its radius of another sphere or a plane.
        let glass_beside = count(|s| {
            s.objects.iter().any(|glass| {
                let ShapeDesc::Sphere { center, radius } = glass.shape else {
                    return false;
                };
                let (c, r) = (f64s(center), f64::from(radius));
                glass.material.transmission >= 0.9
                    && s.objects.iter().any(|other| {
                        !std::ptr::eq(other, glass) && gap(&other.shape, c, r).abs() < 0.1 * r
                    })
            })
        });
        assert!(
            glass_beside > 10,
            "{glass_beside} scenes with glass beside a neighbour"
        );
        // Planes at the world's edge: just inside it.
        let at_the_edge = |s: &OwnedScene| {
            let eye = Vec3::from_f32(s.camera.eye);
            s.objects.iter().any(|o| {
                let h = range::clearance(o, eye);
                matches!(o.shape, ShapeDesc::Plane { .. })
                    && h <= f64::from(s.far)
                    && f64::from(s.far) <= 1.01 * h
            })
        };
        assert!(count(at_the_edge) > 15);
    }
}
