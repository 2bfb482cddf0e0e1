// The <transform> property of a Mitsuba XML element: its steps (translate, scale, rotate, matrix, lookat).
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "xml_props.h"

namespace mcval {

Transform XmlProps::getTransform(const std::string &name) {
    const auto node = find(name, "transform");
    return node ? parseTransform(node) : Transform();
}

Transform XmlProps::parseTransform(const pugi::xml_node &node) const {
    Transform result;
    for (pugi::xml_node step : node.children()) {
        if (step.type() != pugi::node_element) continue;
        try {
            result = parseTransformStep(step) * result;  // later steps apply after earlier ones
        } catch (const std::domain_error &e) {
            m_ctx.fail(step, e.what());  // singular or overflowing: Transform knows no file or line
        }
    }
    return result;
}

Transform XmlProps::parseTransformStep(const pugi::xml_node &step) const {
    const std::string tag = step.name();
    const auto triple = [&](float def) {
        if (step.attribute("value")) return parseTriple(step, m_ctx.attr(step, "value"));
        const auto c = [&](const char *a) { return step.attribute(a) ? parseFloat(step, m_ctx.attr(step, a)) : def; };
        return Vec3f(c("x"), c("y"), c("z"));
    };
    if (tag == "translate") return Transform::translate(triple(0.f));
    if (tag == "scale") return Transform::scale(triple(1.f));
    if (tag == "rotate") {
        if (!step.attribute("angle")) m_ctx.fail(step, "missing angle=\"degrees\"");
        const Vec3f axis = triple(0.f);
        if (squaredNorm(axis) == 0.f) m_ctx.fail(step, "rotation axis is zero: give x, y or z");
        // Mitsuba 3 uses the axis as given: a non-unit one makes its rotation a shear, ours would not.
        const double length = std::sqrt(double(axis.x) * axis.x + double(axis.y) * axis.y + double(axis.z) * axis.z);
        if (!(std::abs(length - 1.0) <= 1e-5)) {
            std::ostringstream msg;
            msg << "rotate axis (" << axis.x << ", " << axis.y << ", " << axis.z << ") has length "
                << std::setprecision(4) << length
                << ", not 1: Mitsuba 3 would shear with it (it does not normalise); give a unit axis";
            m_ctx.fail(step, msg.str());
        }
        return Transform::rotate(axis, parseFloat(step, m_ctx.attr(step, "angle")));
    }
    if (tag == "matrix") {
        const auto parts = splitNumbers(m_ctx.attr(step, "value"));
        if (parts.size() != 16) m_ctx.fail(step, "expected 16 numbers in value");
        float a[16];
        for (int i = 0; i < 16; ++i) a[i] = parseFloat(step, parts[i]);
        return Transform(a);
    }
    if (tag == "lookat") {
        const auto vec = [&](const char *a, bool required) {
            if (!step.attribute(a)) {
                if (required) m_ctx.fail(step, std::string("missing ") + a + "=\"x, y, z\"");
                return Vec3f(0.f, 1.f, 0.f);
            }
            return parseTriple(step, m_ctx.attr(step, a));
        };
        const Vec3f origin = vec("origin", true), target = vec("target", true), up = vec("up", false);
        const Vec3f dir = target - origin;
        if (!std::isfinite(squaredNorm(dir))) m_ctx.fail(step, "origin and target are too far apart for float32");
        if (!(squaredNorm(dir) > 0.f)) m_ctx.fail(step, "origin and target coincide");
        if (!(squaredNorm(cross(normalize(up), normalize(dir))) > 1e-12f))
            m_ctx.fail(step, "up is zero or parallel to the view direction");
        return Transform::lookAt(origin, target, up);
    }
    m_ctx.fail(step, "unsupported transform step: expected translate, scale, rotate, matrix or lookat");
}

}  // namespace mcval
