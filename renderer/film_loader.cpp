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
    // The crop window, as Mitsuba's Film reads it: within the film, the whole film by default.
    film.cropX = props.getInt("crop_offset_x", 0);
    film.cropY = props.getInt("crop_offset_y", 0);
    props.requireRange("crop_offset_x", film.cropX, 0, film.width - 1);
    props.requireRange("crop_offset_y", film.cropY, 0, film.height - 1);
    film.cropWidth = props.getInt("crop_width", film.width);
    film.cropHeight = props.getInt("crop_height", film.height);
    if (film.cropWidth < 1 || film.cropX + film.cropWidth > film.width)
        props.failAt("crop_width", "the crop window must lie within the film: crop_offset_x + crop_width = " +
                                       std::to_string(film.cropX) + " + " + std::to_string(film.cropWidth) +
                                       ", width " + std::to_string(film.width));
    if (film.cropHeight < 1 || film.cropY + film.cropHeight > film.height)
        props.failAt("crop_height", "the crop window must lie within the film: crop_offset_y + crop_height = " +
                                        std::to_string(film.cropY) + " + " + std::to_string(film.cropHeight) +
                                        ", height " + std::to_string(film.height));
    film.sampleBorder = props.getBool("sample_border", false);
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
    props.finish("width, height, crop_offset_x, crop_offset_y, crop_width, crop_height, sample_border, "
                 "pixel_format, component_format, file_format");
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
        } else if (type == "tent") {
            film.filter.type = FilterSpec::Type::Tent;
            film.filter.tentRadius = rp.getFloat("radius", 1.f);
            rp.requireRange("radius", film.filter.tentRadius, kMinTentRadius, kMaxTentRadius);
            rp.finish("radius");
        } else {
            ctx.fail(f, "unsupported rfilter type \"" + type + "\": expected box, gaussian or tent");
        }
        if (!rp.objects().empty()) ctx.fail(rp.objects()[0], "unexpected element inside <rfilter>");
    }
}

}  // namespace mcval
