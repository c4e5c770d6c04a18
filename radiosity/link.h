// Link: one light transfer between two nodes of the hierarchy (HSA91), gathered as
//   H_receiver += F * V * B_source
// where H is irradiance and B radiosity (both radiosity units), F the unoccluded transfer
// coefficient (the form factor F_{receiver -> source} for two elements; the cluster
// kernels of transfer.h otherwise) and V in [0, 1] the visibility attenuation.
#pragma once

#include <cstdint>

namespace radiosity {

/// Loscos et al. 2000, §2.3: a link is VISIBLE (V = 1), INVISIBLE (V = 0) or PARTIAL.
enum class VisibilityType : uint8_t { visible, invisible, partial };

struct Link {
    int receiver = -1;  ///< node that gathers
    int source = -1;    ///< node whose radiosity is gathered
    double F = 0;       ///< unoccluded transfer coefficient, dimensionless
    float V = 1;        ///< visibility attenuation in [0, 1]
    VisibilityType type = VisibilityType::visible;
    uint8_t rays = 0;         ///< visibility rays cast for this link (0: decided by its shaft)
    bool shaftEmpty = false;  ///< no occluder in the shaft: VISIBLE without rays
    /// Passive links only: its subtree was replaced by an active copy of it (a dynamic
    /// update found it entirely blocked); the tree walk then skips it.
    bool retired = false;
    /// The passive link this one was refined from (index into the solver's passive list),
    /// -1 for a top link. Links form a tree by it (the line-space hierarchy of Drettakis &
    /// Sillion 1997), whose shafts the dynamic updates walk from the top.
    int parent = -1;
    /// A link from a light whose V carries its receiver's link correction of real-shadow
    /// removal (Node::lightCorrection): visibility measured again is multiplied by it.
    bool corrected = false;
};
static_assert(sizeof(Link) == 32, "a link is 32 bytes: millions of them are kept");

/// Makes `link` VISIBLE without rays: the shaft between its two nodes holds no occluder
/// (Haines & Wallace 1991).
inline void setShaftEmpty(Link& link) {
    link.V = 1;
    link.type = VisibilityType::visible;
    link.rays = 0;
    link.shaftEmpty = true;
}

/// True while the visibility of `link` is still to be evaluated: no ray was cast for it and
/// its shaft was not found empty.
inline bool needsVisibility(const Link& link) {
    return link.rays == 0 && !link.shaftEmpty;
}

}  // namespace radiosity
