# The Debian packages (`cmake --build build/release --target package`): one
# per component, named after its program, versioned as the project, their
# library dependencies worked out by dpkg-shlibdeps from the binaries.
#   umf-provider   the provider, umf-browser-host, the phone page, the shipped
#                  fields, the browser extension (and the GNOME Shell
#                  extension, which the program carries: umf-provider gnome
#                  install), the menu entry, icon, AppStream data, user unit
#   umf-requester  the webcam requester
#   umf-field      the field tool
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME umf)
set(CPACK_PACKAGE_VENDOR "umf")
set(CPACK_PACKAGE_CONTACT "${UMF_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/packages)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION net)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://umf.github.io/")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_COMPONENTS_ALL provider requester field)

set(CPACK_DEBIAN_PROVIDER_PACKAGE_NAME umf-provider)
set(CPACK_COMPONENT_PROVIDER_DESCRIPTION
"point a phone at the screen and take what is there
The umf provider mixes a faint, pulsing marker field into the screen and
serves, over TLS, what lies under the point a paired phone or webcam aims
at: a window's document, a browser page's link, picture or passage, or a
file pinned to the region. Phones put files and links there too. It runs on
X11, Sway and other wlroots compositors, GNOME Shell and KDE Plasma, or
headless as a board for kiosks (a systemd user unit).")
set(CPACK_DEBIAN_PROVIDER_PACKAGE_SECTION net)
# Found at run time, not linked: the Avahi daemon announces the screen, the
# Wayland platform plugin runs Qt natively on Wayland desktops.
set(CPACK_DEBIAN_PROVIDER_PACKAGE_RECOMMENDS "avahi-daemon, qt6-wayland")
set(CPACK_DEBIAN_PROVIDER_PACKAGE_SUGGESTS "umf-requester, umf-field")

set(CPACK_DEBIAN_REQUESTER_PACKAGE_NAME umf-requester)
set(CPACK_COMPONENT_REQUESTER_DESCRIPTION
"take what a screen shows by pointing a webcam at it
umf-requester finds a screen's marker field in camera frames, videos or
photos, works out the point aimed at, and takes what the umf provider on
that screen serves there (a link or a file), or puts a file or link there.
It pairs with screens, keeps them, and finds them on the local network.")
set(CPACK_DEBIAN_REQUESTER_PACKAGE_SECTION net)
set(CPACK_DEBIAN_REQUESTER_PACKAGE_RECOMMENDS "avahi-daemon, libnss-mdns")

set(CPACK_DEBIAN_FIELD_PACKAGE_NAME umf-field)
set(CPACK_COMPONENT_FIELD_DESCRIPTION
"make, check and print uniform marker fields
umf-field generates marker fields whose every window is unique in all
four orientations, proves a field so, reports how full it is, and renders
it as PNG, SVG or PDF at a given module size for print.")
set(CPACK_DEBIAN_FIELD_PACKAGE_SECTION graphics)

include(CPack)
