// Which handler takes a request: routes in the order they were added, each a
// path (the target without its query) or a prefix of the target, for any
// method or for some only; the first that matches takes the request.
#pragma once

#include <boost/beast/http/verb.hpp>
#include <algorithm>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace umf::provider {

template <class Handler>
class RouteTable {
public:
    using Methods = std::vector<boost::beast::http::verb>;  // empty: any method

    // Every target that starts with `prefix` ("" for every target).
    void add_prefix(std::string prefix, Handler handler, Methods methods = {}) {
        routes_.push_back({std::move(prefix), true, std::move(methods), std::move(handler)});
    }
    // The targets whose path is `path`, whatever their query.
    void add_path(std::string path, Handler handler, Methods methods = {}) {
        routes_.push_back({std::move(path), false, std::move(methods), std::move(handler)});
    }
    // The handler of the first route that takes this request; null when none does.
    const Handler* find(boost::beast::http::verb method, std::string_view target) const {
        const std::string_view path = target.substr(0, target.find('?'));
        for (const auto& route : routes_) {
            const bool matches = route.prefix ? target.starts_with(route.pattern) : path == route.pattern;
            if (!matches) continue;
            if (!route.methods.empty() &&
                std::find(route.methods.begin(), route.methods.end(), method) == route.methods.end())
                continue;
            return &route.handler;
        }
        return nullptr;
    }

private:
    struct Route {
        std::string pattern;
        bool prefix;
        Methods methods;
        Handler handler;
    };
    std::vector<Route> routes_;
};

}  // namespace umf::provider
