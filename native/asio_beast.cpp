// Boost.Asio (with its SSL part) and Boost.Beast compiled once for the
// programs that use them, rather than inline in every file that includes them:
// their non-template code was most of what each network file took to build.
// Every file of a program that links umf_asio_beast sees
// BOOST_ASIO_SEPARATE_COMPILATION and BOOST_BEAST_SEPARATE_COMPILATION
// (native/CMakeLists.txt), so it declares what is defined here.
#include <boost/asio/impl/src.hpp>
#include <boost/asio/ssl/impl/src.hpp>
#include <boost/beast/src.hpp>
