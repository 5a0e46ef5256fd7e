//! Contact manifolds recomputed at every step.
//!
//! parry keeps a manifold's points from one step to the next while the shapes barely move
//! relative to each other (`ContactManifold::try_update_contacts`: less than 1 mm and 1°
//! per step). It moves each point on the first shape to the projection of its partner and
//! never checks that the point is still on that shape, so a contact that slides steadily
//! (a hand dragged along a box's face at 6 cm/s moves 0.06 mm per step) is never
//! recomputed: the box's corner kept pressing on the hand's edge 4 cm beyond the hand's
//! end after the hand had slid past it, and that phantom contact held the box from
//! turning (BENCHMARKS.md, "Phantom contacts in the 3D engine"). This dispatcher clears
//! the points before parry computes the manifold afresh, then hands the old points'
//! solver data (warm-start impulses) to the new ones with the same features.

use rapier3d_f64::geometry::{ContactData, ContactManifoldData};
use rapier3d_f64::parry::query::{
    self, ClosestPoints, Contact, ContactManifold, ContactManifoldsWorkspace,
    DefaultQueryDispatcher, NonlinearRigidMotion, PersistentQueryDispatcher, QueryDispatcher,
    ShapeCastHit, ShapeCastOptions, Unsupported,
};
use rapier3d_f64::parry::shape::Shape;
use rapier3d_f64::prelude::{Isometry, Real, Vector};

type Manifold = ContactManifold<ContactManifoldData, ContactData>;

/// parry's dispatcher, with manifolds that do not persist their points.
pub struct FreshContacts;

impl QueryDispatcher for FreshContacts {
    fn intersection_test(
        &self,
        pos12: &Isometry<Real>,
        g1: &dyn Shape,
        g2: &dyn Shape,
    ) -> Result<bool, Unsupported> {
        DefaultQueryDispatcher.intersection_test(pos12, g1, g2)
    }

    fn distance(
        &self,
        pos12: &Isometry<Real>,
        g1: &dyn Shape,
        g2: &dyn Shape,
    ) -> Result<Real, Unsupported> {
        DefaultQueryDispatcher.distance(pos12, g1, g2)
    }

    fn contact(
        &self,
        pos12: &Isometry<Real>,
        g1: &dyn Shape,
        g2: &dyn Shape,
        prediction: Real,
    ) -> Result<Option<Contact>, Unsupported> {
        DefaultQueryDispatcher.contact(pos12, g1, g2, prediction)
    }

    fn closest_points(
        &self,
        pos12: &Isometry<Real>,
        g1: &dyn Shape,
        g2: &dyn Shape,
        max_dist: Real,
    ) -> Result<ClosestPoints, Unsupported> {
        DefaultQueryDispatcher.closest_points(pos12, g1, g2, max_dist)
    }

    fn cast_shapes(
        &self,
        pos12: &Isometry<Real>,
        local_vel12: &Vector<Real>,
        g1: &dyn Shape,
        g2: &dyn Shape,
        options: ShapeCastOptions,
    ) -> Result<Option<ShapeCastHit>, Unsupported> {
        DefaultQueryDispatcher.cast_shapes(pos12, local_vel12, g1, g2, options)
    }

    fn cast_shapes_nonlinear(
        &self,
        motion1: &NonlinearRigidMotion,
        g1: &dyn Shape,
        motion2: &NonlinearRigidMotion,
        g2: &dyn Shape,
        start_time: Real,
        end_time: Real,
        stop_at_penetration: bool,
    ) -> Result<Option<ShapeCastHit>, Unsupported> {
        DefaultQueryDispatcher.cast_shapes_nonlinear(
            motion1,
            g1,
            motion2,
            g2,
            start_time,
            end_time,
            stop_at_penetration,
        )
    }
}

impl PersistentQueryDispatcher<ContactManifoldData, ContactData> for FreshContacts {
    fn contact_manifolds(
        &self,
        pos12: &Isometry<Real>,
        g1: &dyn Shape,
        g2: &dyn Shape,
        prediction: Real,
        manifolds: &mut Vec<Manifold>,
        workspace: &mut Option<ContactManifoldsWorkspace>,
    ) -> Result<(), Unsupported> {
        // A composite shape keeps one manifold per pair of sub-shapes: each is matched
        // with its own old points.
        let old: Vec<_> = manifolds
            .iter_mut()
            .map(|m| ((m.subshape1, m.subshape2), std::mem::take(&mut m.points)))
            .collect();
        DefaultQueryDispatcher
            .contact_manifolds(pos12, g1, g2, prediction, manifolds, workspace)?;
        for manifold in manifolds.iter_mut() {
            let pair = (manifold.subshape1, manifold.subshape2);
            if let Some((_, points)) = old.iter().find(|(p, _)| *p == pair) {
                manifold.match_contacts(points);
            }
        }
        Ok(())
    }

    fn contact_manifold_convex_convex(
        &self,
        pos12: &Isometry<Real>,
        g1: &dyn Shape,
        g2: &dyn Shape,
        normal_constraints1: Option<&dyn query::details::NormalConstraints>,
        normal_constraints2: Option<&dyn query::details::NormalConstraints>,
        prediction: Real,
        manifold: &mut Manifold,
    ) -> Result<(), Unsupported> {
        let old = std::mem::take(&mut manifold.points);
        DefaultQueryDispatcher.contact_manifold_convex_convex(
            pos12,
            g1,
            g2,
            normal_constraints1,
            normal_constraints2,
            prediction,
            manifold,
        )?;
        manifold.match_contacts(&old);
        Ok(())
    }
}

#[cfg(test)]
#[allow(non_snake_case)] // frame-named poses: X_WP, the pusher's pose in the world
mod tests {
    use super::*;
    use rapier3d_f64::parry::query::PointQuery;
    use rapier3d_f64::parry::shape::Cuboid;
    use std::f64::consts::FRAC_PI_4;

    /// A square pusher (turned 45° about z, its vertical edge pressed 0.5 mm into a box's
    /// -y face) slides 6 cm along the face in 0.05 mm steps, as a hand does at 5 cm/s at
    /// the engine's 1 kHz. Every contact point must lie on both shapes (within 0.1 mm),
    /// checked by projecting it onto each. Returns the worst point's distance from the
    /// pusher (m) over the slide.
    fn worst_point_off_the_pusher(
        dispatcher: &dyn PersistentQueryDispatcher<ContactManifoldData, ContactData>,
    ) -> f64 {
        let pusher = Cuboid::new(Vector::new(0.03, 0.03, 0.08));
        let boxed = Cuboid::new(Vector::new(0.05, 0.05, 0.07));
        let edge = 0.03 * std::f64::consts::SQRT_2; // the edge's distance from the axis
        let mut manifolds: Vec<Manifold> = Vec::new();
        let mut workspace = None;
        let mut worst: f64 = 0.0;
        for step in 0..=1200 {
            let x = -0.03 + 0.05e-3 * step as f64;
            let X_WP = Isometry::new(
                Vector::new(x, -0.05 - edge + 5e-4, 0.0),
                Vector::z() * FRAC_PI_4,
            );
            let X_WB = Isometry::identity();
            let X_PB = X_WP.inverse() * X_WB;
            dispatcher
                .contact_manifolds(&X_PB, &pusher, &boxed, 2e-3, &mut manifolds, &mut workspace)
                .expect("cuboids are supported");
            let points: Vec<_> = manifolds
                .iter()
                .flat_map(|m| &m.points)
                .filter(|p| p.dist <= 0.0)
                .collect();
            assert!(
                !points.is_empty(),
                "the edge presses on the face at x = {x}"
            );
            for p in points {
                let on_pusher = pusher.project_local_point(&p.local_p1, false);
                let on_box = boxed.project_local_point(&p.local_p2, false);
                worst = worst.max((on_pusher.point - p.local_p1).norm());
                assert!(
                    (on_box.point - p.local_p2).norm() < 1e-4,
                    "a point off the box at x = {x}"
                );
            }
        }
        worst
    }

    #[test]
    fn sliding_contacts_stay_on_the_shapes() {
        // parry's persistent manifolds leave the pusher's points behind as it slides
        // (the reason for this dispatcher; if this ever fails, parry has been fixed).
        assert!(worst_point_off_the_pusher(&DefaultQueryDispatcher) > 0.01);
        assert!(worst_point_off_the_pusher(&FreshContacts) < 1e-4);
    }
}
