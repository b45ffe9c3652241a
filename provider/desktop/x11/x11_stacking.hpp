// The provider's own windows stacked against each other on X11. The field
// and its ring are override-redirect windows that raise themselves over new
// windows; the put cards belong over them. Raising the field and then the
// cards is two restacks, and a compositor that draws between them shows
// the field over a card for a frame. One restack that puts the field right
// under the lowest card leaves no such moment.
#pragma once

class QWindow;

namespace umf::provider {

// `window` directly under `sibling`, both top-level windows of this
// process, in one request. Only on Qt's xcb platform; elsewhere (offscreen)
// nothing happens.
void stack_under(QWindow& window, const QWindow& sibling);

}  // namespace umf::provider
