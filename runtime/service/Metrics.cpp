#include "runtime/service/Metrics.h"

#include <charconv>
#include <cmath>

namespace kiosk::service {

std::string escapeLabelValue(std::string_view value) {
    std::string out;
    out.reserve(value.size());
    for (char c : value) {
        if (c == '\\')
            out += "\\\\";
        else if (c == '"')
            out += "\\\"";
        else if (c == '\n')
            out += "\\n";
        else
            out += c;
    }
    return out;
}

std::string formatValue(double value) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
    char buf[32];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, value);
    return ec == std::errc() ? std::string(buf, end) : "NaN";
}

void MetricsWriter::family(std::string_view name, std::string_view help, Type type) {
    mFamily.assign(name);
    mText += "# HELP ";
    mText += name;
    mText += ' ';
    // HELP text escapes only backslash and newline.
    for (char c : help)
        mText += c == '\n' ? std::string("\\n") : c == '\\' ? "\\\\" : std::string(1, c);
    mText += "\n# TYPE ";
    mText += name;
    mText += type == Type::Counter ? " counter\n"
             : type == Type::Gauge ? " gauge\n"
                                   : " histogram\n";
}

void MetricsWriter::sample(std::string_view suffix, const Labels& labels, double value) {
    mText += mFamily;
    mText += suffix;
    if (!labels.empty()) {
        mText += '{';
        for (std::size_t i = 0; i < labels.size(); ++i) {
            if (i) mText += ',';
            mText += labels[i].first;
            mText += "=\"";
            mText += escapeLabelValue(labels[i].second);
            mText += '"';
        }
        mText += '}';
    }
    mText += ' ';
    mText += formatValue(value);
    mText += '\n';
}

}  // namespace kiosk::service
