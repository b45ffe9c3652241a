// The HTTP connection's route table: the first route that matches a request's
// target and method takes it, paths ignore the query, and a route for some
// methods lets the others fall through to later routes.
#ifdef UMF_PROVIDER_TESTS

#include "provider/net/route_table.hpp"

#include <gtest/gtest.h>

#include <string>

#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"

namespace {

namespace http = boost::beast::http;
using umf::provider::RouteTable;

std::string taken_by(const RouteTable<std::string>& table, http::verb method, std::string_view target) {
    const std::string* handler = table.find(method, target);
    return handler ? *handler : "none";
}

TEST(RouteTable, TheFirstMatchingRouteTakesTheRequest) {
    RouteTable<std::string> table;
    table.add_prefix("/api/", "api");
    table.add_path("/share", "share", {http::verb::post});
    table.add_prefix("/dl/", "download", {http::verb::get, http::verb::head});
    table.add_prefix("", "site", {http::verb::get, http::verb::head});

    EXPECT_EQ(taken_by(table, http::verb::post, "/api/hello"), "api");
    EXPECT_EQ(taken_by(table, http::verb::delete_, "/api/session/x"), "api");
    EXPECT_EQ(taken_by(table, http::verb::get, "/dl/abc?x=1"), "download");
    EXPECT_EQ(taken_by(table, http::verb::head, "/dl/abc"), "download");
    EXPECT_EQ(taken_by(table, http::verb::get, "/index.html"), "site");
    // The empty prefix takes any target, even one not starting with a slash.
    EXPECT_EQ(taken_by(table, http::verb::get, "http://host/dl/abc"), "site");
}

TEST(RouteTable, APathIgnoresTheQueryButNotWhatFollowsIt) {
    RouteTable<std::string> table;
    table.add_path("/share", "share", {http::verb::post});
    EXPECT_EQ(taken_by(table, http::verb::post, "/share"), "share");
    EXPECT_EQ(taken_by(table, http::verb::post, "/share?title=x"), "share");
    EXPECT_EQ(taken_by(table, http::verb::post, "/share/more"), "none");
    EXPECT_EQ(taken_by(table, http::verb::post, "/shares"), "none");
}

TEST(RouteTable, OtherMethodsFallThroughToLaterRoutesOrToNone) {
    RouteTable<std::string> table;
    table.add_path("/share", "share", {http::verb::post});
    table.add_prefix("/dl/", "download", {http::verb::get, http::verb::head});
    table.add_prefix("", "site", {http::verb::get, http::verb::head});
    EXPECT_EQ(taken_by(table, http::verb::get, "/share"), "site");
    EXPECT_EQ(taken_by(table, http::verb::post, "/dl/abc"), "none");
    EXPECT_EQ(taken_by(table, http::verb::put, "/index.html"), "none");
}

// The provider's own table: what each kind of request reaches.
TEST(RouteTable, TheProvidersRoutesTakeWhatTheyServe) {
    const auto service = std::make_shared<umf::provider::Service>(umf::provider::default_service_config(), "token");
    const auto routes = umf::provider::make_http_routes(service);
    const auto& header = routes->on_header;
    const auto& request = routes->on_request;

    // Uploads are taken at their header whatever the method (a GET is told it must be a PUT).
    EXPECT_NE(header.find(http::verb::put, "/up/abc"), nullptr);
    EXPECT_EQ(header.find(http::verb::put, "/up/abc"), header.find(http::verb::get, "/up/abc"));
    EXPECT_NE(header.find(http::verb::post, "/share?x=1"), nullptr);
    EXPECT_NE(header.find(http::verb::post, "/share"), header.find(http::verb::put, "/up/abc"));
    EXPECT_EQ(header.find(http::verb::get, "/share"), nullptr);
    EXPECT_EQ(header.find(http::verb::post, "/api/hello"), nullptr);

    // The HTTPS transport (/api/) is the connection's own, before any route.
    EXPECT_EQ(request.find(http::verb::post, "/api/hello"), nullptr);
    const auto* download = request.find(http::verb::get, "/dl/abc");
    const auto* site = request.find(http::verb::get, "/index.html");
    ASSERT_NE(download, nullptr);
    ASSERT_NE(site, nullptr);
    EXPECT_NE(download, site);
    EXPECT_EQ(request.find(http::verb::head, "/dl/abc"), download);
    EXPECT_EQ(request.find(http::verb::get, "/share"), site);
    // Outside /api/ only GET and HEAD are served (the connection answers 405).
    EXPECT_EQ(request.find(http::verb::post, "/dl/abc"), nullptr);
    EXPECT_EQ(request.find(http::verb::post, "/index.html"), nullptr);
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
