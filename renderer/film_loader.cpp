// The <film> of a sensor: Mitsuba's hdrfilm and its reconstruction filter.
#include "film_loader.h"

#include "scene_limits.h"

namespace mcval {

void loadFilm(const XmlContext &ctx, const pugi::xml_node &node, FilmSpec &film) {
    if (ctx.attr(node, "type") != "hdrfilm") ctx.fail(node, "unsupported film type: expected \"hdrfilm\"");
    XmlProps props(ctx, node);
    film.width = props.getInt("width", 768);
    film.height = props.getInt("height", 576);
    props.requireRange("width", film.width, 1, kMaxFilmSide);
    props.requireRange("height", film.height, 1, kMaxFilmSide);
    // Output formats: we always write an RGB OpenEXR; its component type is honoured.
    const std::string pixelFormat = props.getString("pixel_format", "rgb");
    if (pixelFormat != "rgb" && pixelFormat != "rgba")
        ctx.fail(node, "pixel_format \"" + pixelFormat + "\" is not supported: expected rgb or rgba");
    const std::string fileFormat = props.getString("file_format", "openexr");
    if (fileFormat != "openexr" && fileFormat != "exr")
        ctx.fail(node, "file_format \"" + fileFormat + "\" is not supported: expected openexr");
    film.componentFormat = props.getString("component_format", "float32");
    if (film.componentFormat != "float16" && film.componentFormat != "float32")
        ctx.fail(node, "component_format \"" + film.componentFormat +
                    "\" is not supported: expected float16 or float32");
    props.finish("width, height, pixel_format, component_format, file_format");
    for (const auto &f : props.objects()) {
        if (std::string(f.name()) != "rfilter") ctx.fail(f, "unsupported element in <film>: expected <rfilter>");
        const std::string type = ctx.attr(f, "type");
        XmlProps rp(ctx, f);
        if (type == "box") {
            film.filter.type = FilterSpec::Type::Box;
            rp.finish("no properties");
        } else if (type == "gaussian") {
            film.filter.type = FilterSpec::Type::Gaussian;
            film.filter.stddev = rp.getFloat("stddev", 0.5f);
            rp.requireRange("stddev", film.filter.stddev, kMinFilterStddev, kMaxFilterStddev);
            rp.finish("stddev");
        } else {
            ctx.fail(f, "unsupported rfilter type \"" + type + "\": expected box or gaussian");
        }
        if (!rp.objects().empty()) ctx.fail(rp.objects()[0], "unexpected element inside <rfilter>");
    }
}

}  // namespace mcval
