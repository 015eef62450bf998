#include "runtime/vulkan/buffer_group.h"

#include <cstdint>

#include "hmblur/context.h"
#include "hmblur/error.h"

namespace hmb::vk {

void BufferGroup::bind(Bindings& bindings, uint32_t firstBinding, bool byAddress,
                       std::span<const Buffer* const> members) const {
  if (!byAddress) {
    for (const Buffer* member : members) bindings.push_back({firstBinding++, member});
    return;
  }
  const Context& context = members.front()->context();
  if (!context.info().bufferDeviceAddress)
    throw Error("binding '" + members.front()->name() + "' and its group by address needs buffer device addresses, which the device lacks");
  std::vector<VkDeviceAddress> addresses;
  for (const Buffer* member : members) addresses.push_back(member->address());
  if (!table_.handle() || addresses != addresses_) {
    // In host-visible memory: written here without a staging copy or a wait, so binding a
    // group by address while recording an engine's frame submits nothing. A few words,
    // which a GPU's caches keep after the first read.
    table_ = Buffer(context, addresses.size() * sizeof(VkDeviceAddress), MemoryUse::Upload,
                    members.front()->name() + " (address table)");
    table_.upload(std::span<const VkDeviceAddress>(addresses));
    addresses_ = std::move(addresses);
  }
  bindings.push_back({firstBinding, &table_});
}

}  // namespace hmb::vk
