//! The operation counter: [`Counted`], a number format that computes exactly as the format it
//! wraps (the same bits, the same branches) and tallies every product, quotient, root and sum
//! the tracer forms, by the phase of a pixel's work it belongs to, and every object test and
//! box test of a mesh's hierarchy ([`Work`]). From the tests it also tallies the floor of the
//! intersection work: what a tracer that knew which object each ray meets would still do (in a
//! mesh, the test of the triangle it meets, without the boxes).
//!
//! What counts as one operation is the textbook's, whatever a format does inside: a product,
//! a quotient (a reciprocal is one), a root (a reciprocal root is one) and a sum or difference
//! each count one; a dot product three products and two sums; a unit vector (with its length)
//! seven products, two sums and a root; a − b·c·d's edge function two products and a sum; an
//! integer power as many products as repeated squaring takes; a colour channel's quantisation a
//! product and a sum; a product of a narrow number ([`Scalar::Narrow`]) a product. Comparisons,
//! negations and conversions (to and from the narrow format too) count nothing.
//!
//! An operation's phase is the one the core's module that forms it declares
//! ([`obscura::phase`]; the core's vector and colour operations pass their caller's place on,
//! `#[track_caller]`): the camera's, the shapes', the shadow cones', the shading's (and a
//! shape's surface point, normal and pattern once its test is over), the pixel loop's and the
//! colours'. The helpers every phase calls (vectors, rays, roots, sample patterns, the number
//! formats) count for the phase that called them; everything from a [`Work::Test`] on is the
//! test's until another phase's module forms an operation.

use obscura::Scalar;
use obscura::scalar::Precision;
use obscura::scalar::{RayKind, Work};
use std::cell::RefCell;
use std::cmp::Ordering;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};
use std::panic::Location;

/// Format `S`, counting (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
#[repr(transparent)]
pub struct Counted<S>(pub S);

/// Products, quotients, roots and sums.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Operations {
    /// Products.
    pub products: u64,
    /// Quotients and reciprocals.
    pub quotients: u64,
    /// Square roots and reciprocal square roots.
    pub roots: u64,
    /// Sums and differences.
    pub sums: u64,
}

impl Operations {
    const fn new(products: u64, quotients: u64, roots: u64, sums: u64) -> Self {
        Self {
            products,
            quotients,
            roots,
            sums,
        }
    }

    /// Every operation, whatever its kind.
    pub const fn total(self) -> u64 {
        self.products + self.quotients + self.roots + self.sums
    }

    const PRODUCT: Self = Self::new(1, 0, 0, 0);
    const QUOTIENT: Self = Self::new(0, 1, 0, 0);
    const ROOT: Self = Self::new(0, 0, 1, 0);
    const SUM: Self = Self::new(0, 0, 0, 1);
    const DOT: Self = Self::new(3, 0, 0, 2);
    const UNIT_VECTOR: Self = Self::new(7, 0, 1, 2);
    const EDGE: Self = Self::new(2, 0, 0, 1);
    const QUANTISATION: Self = Self::new(1, 0, 0, 1);
}

impl Add for Operations {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Self::new(
            self.products + rhs.products,
            self.quotients + rhs.quotients,
            self.roots + rhs.roots,
            self.sums + rhs.sums,
        )
    }
}

impl AddAssign for Operations {
    fn add_assign(&mut self, rhs: Self) {
        *self = *self + rhs;
    }
}

impl Mul<u64> for Operations {
    type Output = Self;
    fn mul(self, n: u64) -> Self {
        Self::new(
            self.products * n,
            self.quotients * n,
            self.roots * n,
            self.sums * n,
        )
    }
}

/// The phases of a pixel's work the counter tells apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Primary rays: the camera.
    Camera,
    /// Object tests, of every kind of ray.
    Tests,
    /// Which objects a shadow ray tests: their cones.
    Cones,
    /// Shading: lights, shadow and secondary rays set up, surface points and normals.
    Shading,
    /// The pixel loop, samples averaged, colours quantised for the display.
    Output,
    /// Anything else the core computes (the scene build, the camera's set-up).
    Setup,
}

impl Phase {
    /// The phase of an operation formed in the source file `file`, as the core's module there
    /// declares it ([`obscura::phase`]): `None` for a helper's (numbers, vectors, rays, sample
    /// patterns), whose operations are its caller's.
    fn of(file: &str) -> Option<Self> {
        use obscura::phase::Phase as Declared;
        Some(match obscura::phase::module_of_file(file)?.phase? {
            Declared::Camera => Self::Camera,
            Declared::Tests => Self::Tests,
            Declared::Cones => Self::Cones,
            Declared::Shading | Declared::ShadowRays | Declared::SecondaryRays => Self::Shading,
            Declared::Output => Self::Output,
            Declared::Culling | Declared::Words | Declared::Build => Self::Setup,
            Declared::Arithmetic => return None,
        })
    }
}

/// What the counter has seen since it was last [taken](take).
#[derive(Clone, Debug, Default)]
pub struct Tally {
    /// Operations by phase, but the tests.
    pub camera: Operations,
    /// See [`Self::camera`].
    pub cones: Operations,
    /// See [`Self::camera`].
    pub shading: Operations,
    /// See [`Self::camera`].
    pub output: Operations,
    /// See [`Self::camera`].
    pub setup: Operations,
    /// By kind of ray ([`kind_index`]): rays, tests, tests that met their object, and the
    /// tests' operations.
    pub rays: [Rays; 3],
    /// The primary rays the row pass found ([`Work::RowPass`]), which take no unit vector.
    pub row_passed: u64,
    phase: Option<Phase>,
    in_test: bool,
    /// Whether the operations are a box test's, which no floor keeps.
    in_box: bool,
    /// The floor of the object being tested, where a mesh's search met a triangle: the last
    /// such triangle's test (the object's own test is the whole search).
    hit: Option<Operations>,
    searching: Option<RayKind>,
    test: Operations,
    /// The current ray's floor: the operations of the test that met what it meets.
    ray_floor: (Operations, u64),
    /// The source file of the last operation and its phase: the next is most often formed in
    /// the same file, whose phase is then not looked up again.
    last_file: Option<(&'static str, Option<Phase>)>,
}

/// The searches of one kind of ray.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rays {
    /// Rays that searched the scene.
    pub rays: u64,
    /// Object tests (a mesh's triangles each count one).
    pub tests: u64,
    /// Box tests of a mesh's hierarchy.
    pub boxes: u64,
    /// Tests that met their object.
    pub met: u64,
    /// The tests' operations.
    pub operations: Operations,
    /// The floor: the operations and the number of the tests that met the object a ray
    /// finally meets (a primary or secondary ray: the nearest; a shadow ray: every occluder).
    pub floor: (Operations, u64),
}

/// `kind`'s place in [`Tally::rays`].
pub const fn kind_index(kind: RayKind) -> usize {
    match kind {
        RayKind::Primary => 0,
        RayKind::Secondary => 1,
        RayKind::Shadow => 2,
    }
}

impl Tally {
    fn operation(&mut self, operations: Operations, at: &'static Location<'static>) {
        let file = at.file();
        let named = match self.last_file {
            // The same place's file: the same string, by address.
            Some((last, phase)) if std::ptr::eq(last, file) => phase,
            _ => {
                let phase = Phase::of(file);
                self.last_file = Some((file, phase));
                phase
            }
        };
        if named.is_some_and(|phase| phase != Phase::Tests) {
            self.in_test = false;
        }
        let phase = if self.in_test {
            Phase::Tests
        } else {
            match named {
                // A shape's surface point, normal and pattern, asked for by the shading.
                Some(Phase::Tests) => Phase::Shading,
                Some(phase) => phase,
                None => self.phase.unwrap_or(Phase::Setup),
            }
        };
        self.phase = Some(phase);
        match phase {
            Phase::Camera => self.camera += operations,
            Phase::Cones => self.cones += operations,
            Phase::Shading => self.shading += operations,
            Phase::Output => self.output += operations,
            Phase::Setup => self.setup += operations,
            Phase::Tests => {
                if !self.in_box {
                    self.test += operations;
                }
                if let Some(kind) = self.searching {
                    self.rays[kind_index(kind)].operations += operations;
                }
            }
        }
    }

    fn work(&mut self, work: Work) {
        match work {
            Work::Search(kind) => {
                self.end_search();
                self.hit = None;
                self.searching = Some(kind);
                self.rays[kind_index(kind)].rays += 1;
            }
            Work::Test => {
                self.in_test = true;
                self.in_box = false;
                self.phase = Some(Phase::Tests);
                self.test = Operations::default();
                if let Some(kind) = self.searching {
                    self.rays[kind_index(kind)].tests += 1;
                }
            }
            Work::Node => {
                self.in_test = true;
                self.in_box = true;
                self.phase = Some(Phase::Tests);
                if let Some(kind) = self.searching {
                    self.rays[kind_index(kind)].boxes += 1;
                }
            }
            Work::Hit => self.hit = Some(self.test),
            Work::RowPass => self.row_passed += 1,
            Work::Met => {
                let test = self.hit.take().unwrap_or(self.test);
                let Some(kind) = self.searching else { return };
                self.rays[kind_index(kind)].met += 1;
                self.ray_floor = match kind {
                    // The nearest so far: what the ray meets unless a nearer one follows.
                    RayKind::Primary | RayKind::Secondary => (test, 1),
                    RayKind::Shadow => (self.ray_floor.0 + test, self.ray_floor.1 + 1),
                };
            }
        }
    }

    /// Adds the search in progress to its kind's floor.
    fn end_search(&mut self) {
        if let Some(kind) = self.searching.take() {
            let floor = &mut self.rays[kind_index(kind)].floor;
            floor.0 += self.ray_floor.0;
            floor.1 += self.ray_floor.1;
        }
        self.ray_floor = Default::default();
    }
}

thread_local! {
    static TALLY: RefCell<Tally> = RefCell::new(Tally::default());
}

/// Forgets what this thread's counter has seen.
pub fn reset() {
    TALLY.with_borrow_mut(|tally| *tally = Tally::default());
}

/// What this thread's counter has seen since it was last reset, and resets it.
pub fn take() -> Tally {
    TALLY.with_borrow_mut(|tally| {
        tally.end_search();
        std::mem::take(tally)
    })
}

#[track_caller]
fn count(operations: Operations) {
    let at = Location::caller();
    TALLY.with_borrow_mut(|tally| tally.operation(operations, at));
}

/// Products an integer power takes by repeated squaring ([`Scalar::powi`]): one for each bit
/// set, and one squaring between each bit and the next.
const fn power_products(exponent: u16) -> u64 {
    if exponent == 0 {
        0
    } else {
        (exponent.count_ones() + 15 - exponent.leading_zeros()) as u64
    }
}

impl<S: Scalar> Add for Counted<S> {
    type Output = Self;
    #[track_caller]
    fn add(self, rhs: Self) -> Self {
        count(Operations::SUM);
        Self(self.0 + rhs.0)
    }
}

impl<S: Scalar> Sub for Counted<S> {
    type Output = Self;
    #[track_caller]
    fn sub(self, rhs: Self) -> Self {
        count(Operations::SUM);
        Self(self.0 - rhs.0)
    }
}

impl<S: Scalar> Mul for Counted<S> {
    type Output = Self;
    #[track_caller]
    fn mul(self, rhs: Self) -> Self {
        count(Operations::PRODUCT);
        Self(self.0 * rhs.0)
    }
}

impl<S: Scalar> Div for Counted<S> {
    type Output = Self;
    #[track_caller]
    fn div(self, rhs: Self) -> Self {
        count(Operations::QUOTIENT);
        Self(self.0 / rhs.0)
    }
}

impl<S: Scalar> Neg for Counted<S> {
    type Output = Self;
    fn neg(self) -> Self {
        Self(-self.0)
    }
}

impl<S: Scalar> Scalar for Counted<S> {
    const ZERO: Self = Self(S::ZERO);
    const ONE: Self = Self(S::ONE);
    const MAX: Self = Self(S::MAX);
    const FAST_ROOTS: bool = S::FAST_ROOTS;

    fn from_int(n: i32) -> Self {
        Self(S::from_int(n))
    }
    type Narrow = Counted<S::Narrow>;
    #[track_caller]
    fn narrow(self) -> Self::Narrow {
        Counted(self.0.narrow())
    }
    #[track_caller]
    fn mul_narrow(self, k: Self::Narrow) -> Self {
        count(Operations::PRODUCT);
        Self(self.0.mul_narrow(k.0))
    }
    fn from_q16(bits: i32) -> Self {
        Self(S::from_q16(bits))
    }
    fn to_q16(self) -> i32 {
        self.0.to_q16()
    }
    fn floor_int(self) -> i32 {
        self.0.floor_int()
    }
    #[track_caller]
    fn sqrt(self) -> Self {
        count(Operations::ROOT);
        Self(self.0.sqrt())
    }
    #[track_caller]
    fn recip(self) -> Self {
        count(Operations::QUOTIENT);
        Self(self.0.recip())
    }
    #[track_caller]
    fn rsqrt(self) -> Self {
        count(Operations::ROOT);
        Self(self.0.rsqrt())
    }
    #[track_caller]
    fn normalize3(v: [Self; 3], approx: bool) -> ([Self; 3], Self) {
        count(Operations::UNIT_VECTOR);
        let (unit, length) = S::normalize3(v.map(|c| c.0), approx);
        (unit.map(Self), Self(length))
    }
    #[track_caller]
    fn sqrt_approx(self) -> Self {
        count(Operations::ROOT);
        Self(self.0.sqrt_approx())
    }
    #[track_caller]
    fn rsqrt_approx(self) -> Self {
        count(Operations::ROOT);
        Self(self.0.rsqrt_approx())
    }
    #[track_caller]
    fn div_approx(self, rhs: Self) -> Self {
        count(Operations::QUOTIENT);
        Self(self.0.div_approx(rhs.0))
    }
    #[track_caller]
    fn diff_of_products(a: Self, b: Self, c: Self, d: Self) -> (Self, Ordering) {
        count(Operations::EDGE);
        let (difference, sign) = S::diff_of_products(a.0, b.0, c.0, d.0);
        (Self(difference), sign)
    }
    #[track_caller]
    fn dot3(a: [Self; 3], b: [Self; 3]) -> Self {
        count(Operations::DOT);
        Self(S::dot3(a.map(|c| c.0), b.map(|c| c.0)))
    }
    fn abs(self) -> Self {
        Self(self.0.abs())
    }
    fn min(self, other: Self) -> Self {
        Self(self.0.min(other.0))
    }
    fn max(self, other: Self) -> Self {
        Self(self.0.max(other.0))
    }
    fn clamp(self, lo: Self, hi: Self) -> Self {
        Self(self.0.clamp(lo.0, hi.0))
    }
    #[track_caller]
    fn quantize(self, levels: u8, threshold: Self) -> u8 {
        count(Operations::QUANTISATION);
        self.0.quantize(levels, threshold.0)
    }
    #[track_caller]
    fn ratio(num: i32, den: i32) -> Self {
        count(Operations::QUOTIENT);
        Self(S::ratio(num, den))
    }
    fn note(work: Work) {
        TALLY.with_borrow_mut(|tally| tally.work(work));
    }
    #[track_caller]
    fn powi(self, exponent: u16) -> Self {
        count(Operations::PRODUCT * power_products(exponent));
        Self(self.0.powi(exponent))
    }
}

impl<S: Scalar> obscura::scalar::Sealed for Counted<S> {}

impl<S: Scalar> Precision for Counted<S> {
    const NAME: &'static str = S::NAME;

    const RANGE: f64 = S::RANGE;

    const SPLIT: Option<(u32, u32)> = S::SPLIT;

    const UNIT_ERROR: f64 = S::UNIT_ERROR;

    fn from_f64(x: f64) -> Option<Self> {
        S::from_f64(x).map(Self)
    }

    fn to_f64(self) -> f64 {
        self.0.to_f64()
    }

    fn resolution(magnitude: f64) -> f64 {
        S::resolution(magnitude)
    }
}
