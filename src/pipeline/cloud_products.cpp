// Cloud texture products (issue 6): weather map, cloud-type profiles,
// high-altitude templates. Their controls come from the scene's "clouds"
// section (schemas/clouds.schema.json).
#include "pipeline/product_tables.hpp"

namespace skybake {

void add_cloud_products(std::vector<ProductInfo>& r) { (void)r; }

}  // namespace skybake
