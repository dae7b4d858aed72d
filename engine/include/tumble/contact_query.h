// The contacts of a state as the step finds them, asked from outside a run: the editor's
// contact overlay draws them for the frame on screen.
#pragma once

#include <tumble/collision.h>
#include <tumble/model.h>
#include <tumble/state.h>

namespace tumble {

/// How close two surfaces count as touching in this model: 1e-5 of its largest bounded body's
/// bounding radius (the tolerance the World's step uses); 0 when no body is bounded.
double touchTolerance(const Model& model);

/// Every contact of `state` within touchTolerance(model), with every body taken as awake (a
/// sleeping body rests on its support all the same) and bodies joined by a joint left out,
/// as the step's detection finds them. Empty when nothing in the model can touch, or when
/// `state` is not of this model.
collision::ManifoldList contactsOf(const Model& model, const State& state);

}  // namespace tumble
